#pragma once
// File > Export Mesh: which mesh (entities with a mesh, then mesh assets),
// the file, and the `mesh export` operation's parameters, whose fields come
// from its declaration (scene/mesh_export_operation.h) like the CLI's
// options. The export itself runs in the main window's BackgroundJob.
#include <QDialog>

#include "scene/mesh_export_operation.h"

class QCheckBox;
class QComboBox;
class QLineEdit;
class QSpinBox;

namespace hs::app {

class MeshExportDialog : public QDialog {
  Q_OBJECT
 public:
  // `preferred`: the entity to select first (the editor's selection).
  MeshExportDialog(const scene::SceneState& state, scene::EntityId preferred, const QString& suggestedPath,
                   QWidget* parent = nullptr);
  scene::MeshExportRequest request() const;
  QLineEdit* pathEdit() const { return path_; }
  QComboBox* targetCombo() const { return target_; }

 private:
  void browse();
  void updateLodRange();

  const scene::SceneState& state_;
  QComboBox* target_;
  QLineEdit* path_;
  QSpinBox* lod_;
  QComboBox* format_;
  QComboBox* up_;
  QLineEdit* crs_;
  QSpinBox* dracoBits_;
  QCheckBox* world_;
};

}  // namespace hs::app
