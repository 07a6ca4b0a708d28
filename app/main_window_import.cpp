// MainWindow's mesh import: File > Import Mesh… (file choice, then the
// Import dialog), the plain import of one file (drag and drop, the smoke
// test) and what happens when the worker is done: one undo step, selection,
// framing, warnings and, after a decimation, the error report.
#include <QDir>
#include <QFileInfo>
#include <QStatusBar>

#include "app/error_report_dialog.h"
#include "app/import_dialog.h"
#include "app/import_job.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/selection.h"
#include "app/viewport_widget.h"
#include "scene/mesh_report_text.h"

namespace hs::app {

bool MainWindow::importMeshFile(const QString& path, bool wait) {
  scene::MeshImportRequest request;
  request.files = {path.toStdString()};
  request.import = importOptions();
  return importMeshFiles(request, wait);
}

bool MainWindow::importMeshFiles(const scene::MeshImportRequest& request, bool wait) {
  if (isBusy()) {
    messages_->warning("Another operation is still running; try again when it has finished.");
    return false;
  }
  auto ok = std::make_shared<bool>(false);
  importJob_ = std::make_unique<ImportJob>(request, this);
  connect(importJob_.get(), &ImportJob::finished, this, [this, ok] { onImportFinished(ok.get()); });
  importJob_->start();
  if (!wait) return true;
  importJob_->waitForFinished();
  return *ok;
}

void MainWindow::onImportFinished(bool* ok) {
  scene::ImportedMesh& r = importJob_->result();
  const QString path = importJob_->path();
  const QString name = QFileInfo(path).fileName();
  if (r.cancelled) {
    messages_->info(QString("Import of %1 was cancelled; the scene is unchanged.").arg(name));
    return;
  }
  if (!r.ok()) {
    const QString error = r.error.empty() ? QString("%1: the file could not be read").arg(path)
                                          : QString::fromStdString(r.error);
    messages_->error(error);
    prompts_->showError(this, "Import Mesh",
                        QString("Could not import %1\n%2").arg(QDir::toNativeSeparators(path), error));
    return;
  }
  for (const QString& w : importWarnings(r.import)) messages_->warning(w);
  QString summary = importSummary(r.import);
  if (r.tiles.size() > 1) summary += QString(" from %1 tiles (%L2 border vertices welded)").arg(r.tiles.size()).arg(r.tileBorderVerticesMerged);
  const bool decimated = r.processed && r.process.decimated;
  const Json report = r.processReport;
  const scene::EntityId id = addImportToDocument(doc_, r, path);
  if (id == scene::kNoEntity) {
    messages_->error(QString("%1 was read but could not be added to the scene.").arg(name));
    return;
  }
  rememberDirectory(path);
  selection_->select(id);
  viewport_->frameSelection();
  messages_->info(summary);
  // The processing report in one line (decimation, error, LODs, time), and
  // after a decimation the whole of it: what the user gave up, measured.
  if (const std::string line = scene::processReportSummary(report); !line.empty())
    messages_->info(QString("%1: %2").arg(name, QString::fromStdString(line)));
  for (const std::string& w : scene::processWarnings(report))
    messages_->warning(QString("%1: %2").arg(name, QString::fromStdString(w)));
  if (decimated) showErrorReport(this, QString::fromStdString(doc_.state().find(id)->name), report);
  statusBar()->showMessage(summary, 5000);
  *ok = true;
}

ImportDialog* MainWindow::openImportDialog(const QStringList& paths) {
  if (paths.isEmpty() || isBusy()) return nullptr;
  mesh::ImportOptions defaults = importOptions();
  // Scans usually come with an offset sidecar; without one this reads the
  // file's coordinates as they are.
  defaults.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Auto;
  auto* dialog = new ImportDialog(paths, defaults, this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog, &QDialog::accepted, this, [this, dialog] { importMeshFiles(dialog->request(), false); });
  dialog->open();  // window-modal, returns at once
  return dialog;
}

void MainWindow::requestImport() {
  if (isBusy()) return;
  const QStringList paths = prompts_->askOpenFiles(this, "Import Mesh", lastDirectory(), importFileFilter());
  if (!paths.isEmpty()) openImportDialog(paths);
}

}  // namespace hs::app
