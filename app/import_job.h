#pragma once
// Import Mesh off the UI thread: scene::importMeshFiles (reading, and with
// the Import dialog's options cleaning, decimation and LODs) runs on a worker
// with its progress in a dialog (Cancel stops it), and the result is turned
// into one undoable scene edit on the UI thread.
#include <memory>

#include <QObject>
#include <QString>
#include <QStringList>

#include "mesh/mesh_import.h"
#include "scene/document.h"
#include "scene/import_pipeline.h"

class QWidget;

namespace hs::app {

class BackgroundJob;

class ImportJob : public QObject {
  Q_OBJECT
 public:
  ImportJob(const scene::MeshImportRequest& request, QWidget* dialogParent, QObject* parent = nullptr);
  ~ImportJob() override;

  void start();
  void waitForFinished();
  bool isRunning() const;
  void cancel();
  const QString& path() const { return path_; }  // the first file
  // Valid once finished() was emitted.
  scene::ImportedMesh& result() { return *result_; }

 signals:
  void finished();

 private:
  QString path_;
  scene::MeshImportRequest request_;
  std::shared_ptr<scene::ImportedMesh> result_;
  std::unique_ptr<BackgroundJob> job_;
};

// "Mesh files (*.obj *.fbx ...);;All files (*)", from mesh::supportedExtensions().
QString importFileFilter();
// The entity name for a file: its base name ("stanford-bunny").
QString entityNameForFile(const QString& path);
// One line: what was read, how big, how long.
QString importSummary(const mesh::ImportReport& report);
// The reader's warnings plus a line for each kind of repair it made.
QStringList importWarnings(const mesh::ImportReport& report);
// Adds the mesh (with its LODs and reports) as an asset and an entity at the
// file's own coordinates (scene::ops::addImportedMesh, one undo step).
// Returns the entity id.
scene::EntityId addImportToDocument(scene::Document& doc, scene::ImportedMesh& result, const QString& path);

}  // namespace hs::app
