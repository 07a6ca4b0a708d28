// MainWindow's document operations: new, open, save, unsaved-changes
// questions, crash recovery and the screenshot (importing is in
// main_window_import.cpp). Everything slow runs in a BackgroundJob; the
// document is only touched here, on the UI thread, once the work has finished.
#include <chrono>
#include <optional>

#include <QAction>
#include <QActionGroup>
#include <QDir>
#include <QFileInfo>
#include <QImageWriter>
#include <QLocale>
#include <QMenu>
#include <QPainter>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>

#include "app/autosave.h"
#include "app/background_job.h"
#include "app/import_job.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/recent_files.h"
#include "app/selection.h"
#include "app/viewport_widget.h"
#include "scene/demo_scene.h"
#include "scene/hscene_file.h"
#include "scene/terrain_file.h"

namespace hs::app {
namespace {

const char* kSceneFilter = "Hybridscape scenes (*.hscene);;All files (*)";

}  // namespace

bool MainWindow::isBusy() const {
  return (docJob_ && docJob_->isRunning()) || (importJob_ && importJob_->isRunning());
}

mesh::ImportOptions MainWindow::importOptions() const {
  mesh::ImportOptions o;
  if (QAction* a = upAxisGroup_ ? upAxisGroup_->checkedAction() : nullptr) o.up = mesh::UpAxis(a->data().toInt());
  return o;
}

QString MainWindow::lastDirectory() const {
  return QSettings().value("files/lastDirectory", QDir::homePath()).toString();
}

void MainWindow::rememberDirectory(const QString& file) {
  QSettings().setValue("files/lastDirectory", QFileInfo(file).absolutePath());
}

void MainWindow::loadDemoScene() {
  std::string error;
  std::optional<scene::SceneState> demo = scene::buildDemoScene(error);
  if (!demo) {
    messages_->error("The demo scene could not be built: " + QString::fromStdString(error));
    newScene();
    return;
  }
  untitledName_ = "Demo";
  selection_->clear();
  doc_.reset(std::move(*demo), QString());
  updateTitle();
  messages_->info("Opened the built-in demo scene (save it to keep your changes)");
}

void MainWindow::newScene() {
  untitledName_ = "Untitled";
  selection_->clear();
  doc_.reset(scene::buildStarterScene(), QString());
  updateTitle();
}

bool MainWindow::openSceneFile(const QString& path, bool wait) { return openInternal(path, wait, true, {}); }

bool MainWindow::openInternal(const QString& path, bool wait, bool remember, std::function<void()> onSuccess) {
  if (isBusy()) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return false;
  }
  struct Result {
    std::optional<scene::SceneState> state;
    std::string error;
    scene::LoadReport report;  // a save rolled back, values clamped: shown as warnings
    double seconds = 0.0;
  };
  auto result = std::make_shared<Result>();
  auto ok = std::make_shared<bool>(false);
  const QString name = QFileInfo(path).fileName();
  docJob_ = std::make_unique<BackgroundJob>(this, "Open Scene", QString("Opening %1…").arg(name), true);
  BackgroundJob* job = docJob_.get();
  connect(job, &BackgroundJob::finished, this, [this, job, result, ok, path, name, remember, onSuccess] {
    for (const std::string& w : result->report.warnings) messages_->warning(QString::fromStdString(w));
    if (result->state) {
      const size_t entities = result->state->entities.size(), assets = result->state->assets.size();
      selection_->clear();
      doc_.reset(std::move(*result->state), QFileInfo(path).absoluteFilePath());
      if (remember) {
        RecentFiles::add(path);
        rememberDirectory(path);
        messages_->info(QString("Opened %1: %2 entities, %3 mesh assets in %4 s")
                            .arg(name)
                            .arg(entities)
                            .arg(assets)
                            .arg(result->seconds, 0, 'f', 2));
      }
      *ok = true;
      if (onSuccess) onSuccess();
      updateTitle();
    } else if (job->cancelRequested()) {
      messages_->info(QString("Opening %1 was cancelled; the open scene is unchanged.").arg(name));
    } else {
      const QString error = QString::fromStdString(result->error);
      messages_->error(error);
      prompts_->showError(this, "Open Scene", QString("Could not open %1\n%2").arg(QDir::toNativeSeparators(path), error));
      // A damaged file may still hold most of the work: offer to salvage it
      // (later: this job is still being finished).
      if (error.contains("damaged") &&
          prompts_->askYesNo(this, "Open Scene",
                             QString("%1 is damaged. Save a repaired copy with what can still be read? The file "
                                     "itself is not changed.")
                                 .arg(name),
                             "Save a Repaired Copy…", "Cancel"))
        QTimer::singleShot(0, this, [this, path] { requestRepair(path); });
    }
  });
  const std::string file = path.toStdString();
  job->start([result, file](const Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    result->state = scene::loadScene(file, result->error, &progress, &result->report);
    if (!result->state && result->error.empty()) result->error = file + ": could not be opened";
    result->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  if (!wait) return true;
  job->waitForFinished();
  return *ok;
}

bool MainWindow::saveSceneTo(const QString& path, bool wait) {
  if (isBusy()) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return false;
  }
  struct Result {
    bool ok = false;
    std::string error;
    scene::SaveReport report;
  };
  auto result = std::make_shared<Result>();
  auto ok = std::make_shared<bool>(false);
  // The worker writes a snapshot; edits made meanwhile stay unsaved (the
  // revision check below), so "saved" never claims more than the file holds.
  // Terrain tiles are shared, not copied: freeze them copy-on-write so the
  // worker writes this moment while the user keeps painting.
  auto snapshot = std::make_shared<scene::SceneState>(scene::snapshotForSave(doc_.state()));
  const quint64 revision = revision_;
  const QString abs = QFileInfo(path).absoluteFilePath();
  const QString name = QFileInfo(path).fileName();
  docJob_ = std::make_unique<BackgroundJob>(this, "Save Scene", QString("Saving %1…").arg(name), false);
  BackgroundJob* job = docJob_.get();
  connect(job, &BackgroundJob::finished, this, [this, result, ok, abs, name, revision] {
    if (result->ok) {
      doc_.setFilePath(abs);
      if (revision_ == revision) doc_.markSaved();
      RecentFiles::add(abs);
      rememberDirectory(abs);
      const scene::SaveReport& r = result->report;
      messages_->info(QString("Saved %1 (%2 blobs written, %3 unchanged, %4 in %5 s%6)")
                          .arg(name)
                          .arg(r.blobsWritten)
                          .arg(r.blobsUnchanged)
                          .arg(QLocale().formattedDataSize(qint64(r.bytesWritten)))
                          .arg(r.seconds, 0, 'f', 2)
                          .arg(r.tilesWritten + r.tilesUnchanged
                                   ? QString("; terrain tiles: %1 written, %2 unchanged").arg(r.tilesWritten).arg(r.tilesUnchanged)
                                   : QString()));
      statusBar()->showMessage("Saved " + name, 3000);
      *ok = true;
      updateTitle();
    } else {
      const QString error = QString::fromStdString(result->error);
      messages_->error(error);
      prompts_->showError(this, "Save Scene",
                          QString("Could not save %1\n%2\nThe scene is still open with its changes.")
                              .arg(QDir::toNativeSeparators(abs), error));
    }
  });
  const std::string file = abs.toStdString();
  job->start([result, snapshot, file](const Progress&) {
    result->ok = scene::saveScene(*snapshot, file, result->error, &result->report);
    if (!result->ok && result->error.empty()) result->error = file + ": could not be written";
  });
  if (!wait) return true;
  job->waitForFinished();
  return *ok;
}

bool MainWindow::maybeSave() {
  if (!doc_.isModified()) return true;
  switch (prompts_->askSaveChanges(this, documentTitle())) {
    case Prompts::SaveChoice::Save: return requestSave();
    case Prompts::SaveChoice::Discard: return true;
    case Prompts::SaveChoice::Cancel: return false;
  }
  return false;
}

void MainWindow::requestNew() {
  if (isBusy() || !maybeSave()) return;
  newScene();
}

void MainWindow::requestOpen() {
  if (isBusy() || !maybeSave()) return;
  const QString path = prompts_->askOpenFile(this, "Open Scene", lastDirectory(), kSceneFilter);
  if (!path.isEmpty()) openSceneFile(path, false);
}

void MainWindow::requestOpenRecent(const QString& path) {
  if (isBusy()) return;
  if (!QFileInfo::exists(path)) {
    prompts_->showError(this, "Open Recent", QString("%1 no longer exists\nIt was removed from the list.")
                                                 .arg(QDir::toNativeSeparators(path)));
    RecentFiles::remove(path);
    return;
  }
  if (!maybeSave()) return;
  openSceneFile(path, false);
}

bool MainWindow::requestSave() {
  if (doc_.filePath().isEmpty() || !doc_.filePath().endsWith(".hscene", Qt::CaseInsensitive)) return requestSaveAs();
  return saveSceneTo(doc_.filePath(), true);
}

bool MainWindow::requestSaveAs() {
  const QString suggested = doc_.filePath().isEmpty() ? lastDirectory() + "/" + untitledName_ + ".hscene" : doc_.filePath();
  QString path = prompts_->askSaveFile(this, "Save Scene As", suggested, kSceneFilter);
  if (path.isEmpty()) return false;
  if (QFileInfo(path).suffix().isEmpty()) path += ".hscene";
  return saveSceneTo(path, true);
}

void MainWindow::rebuildRecentMenu() {
  recentMenu_->clear();
  const QStringList files = RecentFiles::list();
  for (int i = 0; i < files.size(); ++i) {
    const QString& f = files[i];
    QAction* a = recentMenu_->addAction(QString("&%1  %2").arg((i + 1) % 10).arg(QFileInfo(f).fileName()));
    a->setStatusTip(QDir::toNativeSeparators(f));
    a->setToolTip(QDir::toNativeSeparators(f));
    connect(a, &QAction::triggered, this, [this, f] { requestOpenRecent(f); });
  }
  if (files.isEmpty()) recentMenu_->addAction("(none)")->setEnabled(false);
  recentMenu_->addSeparator();
  QAction* clear = recentMenu_->addAction("&Clear List", this, [] { RecentFiles::clear(); });
  clear->setEnabled(!files.isEmpty());
}

void MainWindow::offerRecovery() {
  if (isBusy()) {
    // Still opening the file from the command line: ask once that is done.
    QTimer::singleShot(250, this, &MainWindow::offerRecovery);
    return;
  }
  const std::vector<Autosave::Orphan> orphans = autosave_->findOrphans();
  for (const Autosave::Orphan& o : orphans) {
    const QString what = o.documentPath.isEmpty() ? QString("an untitled scene")
                                                  : QString("“%1”").arg(QFileInfo(o.documentPath).fileName());
    const bool recover = prompts_->askYesNo(
        this, "Recover Unsaved Work",
        QString("Hybridscape did not shut down cleanly. A recovery copy of %1 from %2 was found.\n\n"
                "Recover it? (Discard deletes the copy.)")
            .arg(what, QLocale().toString(o.savedAt, QLocale::ShortFormat)),
        "Recover", "Discard");
    if (!recover) {
      Autosave::discard(o);
      messages_->info("Discarded a recovery copy of " + what);
      continue;
    }
    if (doc_.isModified() && !maybeSave()) return;
    const Autosave::Orphan orphan = o;
    openInternal(o.recoveryFile, false, false, [this, orphan, what] {
      // The recovered work is unsaved: it belongs to its original file (or
      // none) and stays modified until the user saves it.
      doc_.setFilePath(orphan.documentPath);
      untitledName_ = "Recovered";
      doc_.undoStack()->resetClean();
      Autosave::discard(orphan);
      autosave_->saveNow();
      messages_->info("Recovered unsaved work of " + what + "; save it to keep it.");
    });
    return;  // one document at a time; others are offered at the next start
  }
}

bool MainWindow::selectByName(const QString& name) {
  const scene::EntityId id = doc_.state().findByName(name.toStdString());
  if (id == scene::kNoEntity) return false;
  selection_->select(id);
  return true;
}

bool MainWindow::writeScreenshot(const QString& path) {
  QPixmap shot = grab();
  // grab() does not reliably include GL content: compose the viewport's own image.
  const QImage gl = viewport_->grabFramebuffer();
  if (!gl.isNull()) {
    QPainter p(&shot);
    p.drawImage(QRect(viewport_->mapTo(this, QPoint(0, 0)), viewport_->size()), gl);
  }
  QDir().mkpath(QFileInfo(path).absolutePath());
  QImageWriter writer(path);
  if (!writer.write(shot.toImage())) {
    messages_->error(QString("%1: %2").arg(path, writer.errorString()));
    return false;
  }
  return true;
}

}  // namespace hs::app
