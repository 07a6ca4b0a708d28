// MainWindow's File > Export Mesh…: the dialog, then the `mesh export`
// operation on a worker (a copy of the document's state: meshes are shared,
// not copied), with progress and Cancel; a message when it is done.
#include <QDir>
#include <QFileInfo>
#include <QStatusBar>

#include "app/background_job.h"
#include "app/main_window.h"
#include "app/mesh_export_dialog.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/selection.h"

namespace hs::app {

std::unique_ptr<MeshExportDialog> MainWindow::makeMeshExportDialog() {
  const scene::SceneState& s = doc_.state();
  QString name = "mesh";
  if (const scene::Entity* e = s.find(selection_->primary()); e && e->mesh) name = QString::fromStdString(e->name);
  const QString suggested = QDir(lastDirectory()).filePath(name.replace(' ', '_') + ".obj");
  return std::make_unique<MeshExportDialog>(s, selection_->primary(), suggested, this);
}

void MainWindow::requestExportMesh() {
  if (doc_.state().assets.empty()) {
    prompts_->showError(this, "Export Mesh", "The scene has no meshes to export.\nImport one with File > Import Mesh.");
    return;
  }
  const std::unique_ptr<MeshExportDialog> dialog = makeMeshExportDialog();
  if (dialog->exec() != QDialog::Accepted) return;
  exportMesh(dialog->request(), false);
}

bool MainWindow::exportMesh(const scene::MeshExportRequest& request, bool wait) {
  if (isBusy() || (exportJob_ && exportJob_->isRunning())) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return false;
  }
  auto state = std::make_shared<const scene::SceneState>(doc_.state());
  auto outcome = std::make_shared<scene::MeshExportOutcome>();
  const QString file = QFileInfo(QString::fromStdString(request.out)).fileName();
  exportJob_ = std::make_unique<BackgroundJob>(this, "Export Mesh", "Exporting " + file + "…", true);
  auto ok = std::make_shared<bool>(false);
  connect(exportJob_.get(), &BackgroundJob::finished, this, [this, outcome, ok, file] {
    if (outcome->result.ok()) {
      *ok = true;
      const QString text = QString("Exported %1 to %2: %L3 triangles")
                               .arg(QString::fromStdString(outcome->what), file)
                               .arg(outcome->result.triangles);
      messages_->info(text);
      for (const std::string& n : outcome->notes) messages_->info(QString::fromStdString(n));
      for (const std::string& w : outcome->result.warnings) messages_->warning(QString::fromStdString(w));
      statusBar()->showMessage(text, 5000);
    } else {
      prompts_->showError(this, "Export Mesh", QString::fromStdString(outcome->result.error));
    }
  });
  exportJob_->start([state, outcome, request](const Progress& progress) {
    *outcome = scene::exportSceneMesh(*state, request, &progress);
  });
  if (!wait) return true;
  exportJob_->waitForFinished();
  return *ok;
}

}  // namespace hs::app
