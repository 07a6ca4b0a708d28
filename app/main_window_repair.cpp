// File > Save a Repaired Copy… (scene/hscene_repair.h): the editor's side of
// `hybridscape-cli repair`.
#include <QDir>
#include <QFileInfo>
#include <QTimer>

#include "app/background_job.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "scene/hscene_repair.h"

namespace hs::app {

namespace {
const char* kFilter = "Hybridscape scenes (*.hscene);;All files (*)";
}

void MainWindow::requestRepair(const QString& given) {
  if (isBusy()) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return;
  }
  const QString damaged =
      given.isEmpty() ? prompts_->askOpenFile(this, "Save a Repaired Copy: the damaged scene", lastDirectory(), kFilter)
                      : given;
  if (damaged.isEmpty()) return;
  const QFileInfo fi(damaged);
  const QString out = prompts_->askSaveFile(this, "Save a Repaired Copy",
                                            fi.absolutePath() + "/" + fi.completeBaseName() + "-repaired.hscene", kFilter);
  if (!out.isEmpty()) repairSceneFile(damaged, out, false);
}

bool MainWindow::repairSceneFile(const QString& damaged, const QString& out, bool wait) {
  if (isBusy()) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return false;
  }
  struct Result {
    bool ok = false;
    std::string error;
    scene::RepairReport report;
  };
  auto result = std::make_shared<Result>();
  auto ok = std::make_shared<bool>(false);
  const QString name = QFileInfo(damaged).fileName();
  docJob_ = std::make_unique<BackgroundJob>(this, "Save a Repaired Copy", QString("Salvaging %1…").arg(name), false);
  BackgroundJob* job = docJob_.get();
  connect(job, &BackgroundJob::finished, this, [this, result, ok, damaged, out, name] {
    if (!result->ok) {
      const QString error = QString::fromStdString(result->error);
      messages_->error(error);
      prompts_->showError(this, "Save a Repaired Copy", QString("No repaired copy of %1 was written\n%2")
                                                            .arg(QDir::toNativeSeparators(damaged), error));
      return;
    }
    const scene::RepairReport& r = result->report;
    for (const std::string& n : r.notes) messages_->info(QString::fromStdString(n));
    for (const std::string& d : r.dropped) messages_->warning("Dropped: " + QString::fromStdString(d));
    messages_->info(QString("Wrote the repaired copy %1: %2 entities, %3 meshes, %4 terrains (%5); %6 is unchanged")
                        .arg(QDir::toNativeSeparators(out))
                        .arg(r.entities)
                        .arg(r.meshes)
                        .arg(r.terrains)
                        .arg(r.wasWhole ? QString("nothing was lost") : QString("%1 thing(s) dropped").arg(r.dropped.size()))
                        .arg(name));
    *ok = true;
    if (prompts_->askYesNo(this, "Save a Repaired Copy",
                           QString("The repaired copy was written (%1 thing(s) dropped, listed in the messages). "
                                   "Open it?")
                               .arg(r.dropped.size()),
                           "Open", "Not Now"))
      QTimer::singleShot(0, this, [this, out] {
        if (maybeSave()) openSceneFile(out, false);
      });
  });
  const std::string from = damaged.toStdString(), to = out.toStdString();
  job->start([result, from, to](const Progress&) {
    result->ok = scene::repairScene(from, to, result->report, result->error);
  });
  if (!wait) return true;
  job->waitForFinished();
  return *ok;
}

}  // namespace hs::app
