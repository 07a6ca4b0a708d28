#pragma once
// Import Mesh off the UI thread: mesh::importMesh runs on a worker with its
// progress in a dialog (Cancel stops the reader), and the result is turned
// into one undoable scene edit on the UI thread.
#include <memory>

#include <QObject>
#include <QString>
#include <QStringList>

#include "mesh/mesh_import.h"
#include "scene/document.h"

class QWidget;

namespace hs::app {

class BackgroundJob;

class ImportJob : public QObject {
  Q_OBJECT
 public:
  ImportJob(const QString& path, const mesh::ImportOptions& options, QWidget* dialogParent,
            QObject* parent = nullptr);
  ~ImportJob() override;

  void start();
  void waitForFinished();
  bool isRunning() const;
  void cancel();
  const QString& path() const { return path_; }
  // Valid once finished() was emitted.
  mesh::ImportResult& result() { return *result_; }

 signals:
  void finished();

 private:
  QString path_;
  mesh::ImportOptions options_;
  std::shared_ptr<mesh::ImportResult> result_;
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
// Adds the mesh as an asset and an entity at the file's own coordinates
// (scene::ops::addImportedMesh, one undo step). Returns the entity id.
scene::EntityId addImportToDocument(scene::Document& doc, mesh::ImportResult& result, const QString& path);

}  // namespace hs::app
