#pragma once
// The Materials dock: the document's materials by name, every field of
// scene::materialFields() editable through the same field editors as the
// Properties dock (textures as a list of the scene's textures), and a
// preview sphere rendered with the selected material. Edits go through
// scene::ops::setMaterialField (undoable, one step per gesture); a refused
// value shows the message that names the material and the field. New adds
// a copy of the material shown; Delete removes one no mesh slot uses.
#include <map>
#include <optional>
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
class KeyButton;
class Keying;
class MaterialPreview;
class TimelineClock;

class MaterialsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit MaterialsPanel(scene::Document& doc, QWidget* parent = nullptr);
  ~MaterialsPanel() override;

  // Key buttons beside each animatable field (they key the material shown
  // at the timeline's frame), values shown at that frame, and edits of
  // animated fields keyed in the same undo step: the Properties dock's
  // behaviour for entity fields (scene/object_tracks.h).
  void enableKeying(Keying& keying, TimelineClock& clock);
  // The key button of field `key` ("roughness"); null before enableKeying.
  KeyButton* keyButtonFor(const std::string& key) const;

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
  void addMaterial();
  void deleteMaterial();
  void showError(const std::string& error);  // under the list and to Messages
  void refreshValues();
  void requestPreview();
  void apply(const scene::MaterialField& field, const scene::FieldValue& value, const QString& mergeKey);
  // What the fields show: the scene at the timeline's frame once keying is on.
  const scene::SceneState& shown() const;

  scene::Document& doc_;
  scene::MaterialId current_ = scene::kNoMaterial;
  QListWidget* list_ = nullptr;
  QLabel* preview_ = nullptr;
  QLabel* error_ = nullptr;
  QWidget* form_ = nullptr;
  std::vector<std::pair<const scene::MaterialField*, FieldEditor*>> rows_;
  std::map<std::string, FieldEditor*> byKey_;
  std::map<std::string, QWidget*> rowOf_;  // the editor's row, where a key button goes
  std::map<std::string, KeyButton*> keyButtons_;
  Keying* keying_ = nullptr;
  TimelineClock* clock_ = nullptr;
  int editCounter_ = 0;
  std::optional<scene::Material> previewed_;  // what the preview last rendered
  std::map<std::string, QComboBox*> textures_;
  MaterialPreview* renderer_ = nullptr;
  QImage* lastImage_ = nullptr;
  bool updating_ = false;
};

}  // namespace hs::app
