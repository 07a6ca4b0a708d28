#pragma once
// The Materials dock: the document's materials by name, every field of
// scene::materialFields() editable through the same field editors as the
// Properties dock (textures as a list of the scene's textures), and a
// preview sphere rendered with the selected material. Edits go through
// scene::ops::setMaterialField (undoable, one step per gesture); a refused
// value shows the message that names the material and the field.
#include <map>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

class QComboBox;
class QLabel;
class QListWidget;

namespace hs::app {

class FieldEditor;
class MaterialPreview;

class MaterialsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit MaterialsPanel(scene::Document& doc, QWidget* parent = nullptr);
  ~MaterialsPanel() override;

  // Shows material `id` (the list follows).
  void select(scene::MaterialId id);
  scene::MaterialId selected() const { return current_; }
  FieldEditor* editorFor(const std::string& key) const;
  QComboBox* textureChooser(const std::string& key) const;
  // The last image the preview delivered (null before the first).
  const QImage& previewImage() const;

 signals:
  void previewUpdated();
  // A texture of the material that cannot be drawn, or a refused value.
  void problem(const QString& message);

 private:
  void rebuildList();
  void refreshValues();
  void requestPreview();
  void apply(const scene::MaterialField& field, const scene::FieldValue& value, const QString& mergeKey);

  scene::Document& doc_;
  scene::MaterialId current_ = scene::kNoMaterial;
  QListWidget* list_ = nullptr;
  QLabel* preview_ = nullptr;
  QLabel* error_ = nullptr;
  QWidget* form_ = nullptr;
  std::vector<std::pair<const scene::MaterialField*, FieldEditor*>> rows_;
  std::map<std::string, FieldEditor*> byKey_;
  std::map<std::string, QComboBox*> textures_;
  MaterialPreview* renderer_ = nullptr;
  QImage* lastImage_ = nullptr;
  bool updating_ = false;
};

}  // namespace hs::app
