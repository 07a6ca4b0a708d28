#pragma once
// The Properties dock: the primary selected entity's fields, one section per
// component, generated from scene::entityComponents(). Edits go through
// scene::ops::setField (undoable); with several entities selected an edit
// applies to each of them that has the field, as one undo step, and a vector
// edit changes only the component that was touched. A value refused by its
// field's rule or clamped by its setter is said through problem().
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

class QFormLayout;
class QLabel;
class QPushButton;
class QToolButton;
class QVBoxLayout;

namespace hs::app {

class FieldEditor;
class MaterialSlotsWidget;
class Selection;

class PropertyPanel : public QWidget {
  Q_OBJECT
 public:
  PropertyPanel(scene::Document& doc, Selection& selection, QWidget* parent = nullptr);

  // The editor of "component.key" (e.g. "transform.translation"), or nullptr.
  FieldEditor* editorFor(const std::string& path) const;

  // Timeline hooks (set by the main window). The values shown and edited
  // (the scene at the timeline's current time; default: the document).
  void setStateSource(std::function<const scene::SceneState&()> source);
  // A widget around each field's editor (the key button beside it).
  void setRowDecorator(std::function<QWidget*(const std::string& path, QWidget* editor, QWidget* parent)> decorator);
  // After an edit of `path` on entities, with the merge key it was pushed
  // with (keys set by the timeline join that undo step).
  void setEditedHook(
      std::function<void(const std::vector<scene::EntityId>& ids, const std::string& path, const QString& mergeKey)> hook);
  // Shows the values again (the timeline's time moved).
  void refreshValues() { refresh(); }
  // Terrain components: "New Terrain…" in Add Component > Terrain and in the
  // component's terrain row calls this with the entity (set by the Terrain
  // panel, which owns the dialog; terrain_component_picker.h).
  void setNewTerrainHook(std::function<void(scene::EntityId showOn)> hook);
  // The material slots of the selected mesh (null without one).
  MaterialSlotsWidget* materialSlots() const { return slots_; }
  // Mesh components: "Materials…" calls this with the mesh's asset (set by
  // the main window: shows the Materials panel on the asset's first material).
  void setMaterialsHook(std::function<void(scene::AssetId asset)> hook) { materialsHook_ = std::move(hook); }
  // What the particles section's "Particles…" button does (show the emitter
  // in the Particles panel, particles_panel.h).
  void setParticlesHook(std::function<void(scene::EntityId emitter)> hook) { particlesHook_ = std::move(hook); }

 signals:
  // A value that was not applied as typed: refused by its field's rule, or
  // clamped by its setter (scene::ops::FieldChange). For Messages.
  void problem(const QString& message);

 private:
  struct Row {
    const scene::ComponentInfo* component;
    const scene::EntityField* field;
    FieldEditor* editor;
  };
  std::function<void(scene::AssetId)> materialsHook_;
  std::function<void(scene::EntityId)> particlesHook_;
  void onDocumentChanged(const scene::ChangeSet& changes);
  // The structure (which sections) depends on the primary entity and its components.
  std::string structureKey() const;
  void rebuild();
  void refresh();
  void apply(const scene::EntityField& field, const scene::ComponentInfo& component, const scene::FieldValue& v,
             int vectorComponent, const QString& mergeKey);
  QWidget* buildSection(const scene::ComponentInfo& c, const scene::Entity& e);
  // The camera section's own post settings (property_panel_camera_post.cpp).
  void buildCameraPost(QFormLayout* form, QWidget* body, const scene::ComponentInfo& camera, const scene::Entity& e);

  scene::Document& doc_;
  Selection& selection_;
  QWidget* content_ = nullptr;
  QVBoxLayout* contentLayout_ = nullptr;
  QLabel* header_ = nullptr;
  QLabel* meshInfo_ = nullptr;
  QPushButton* meshReport_ = nullptr;  // the asset's processing report
  MaterialSlotsWidget* slots_ = nullptr;  // the asset's material slots
  QToolButton* addButton_ = nullptr;
  std::vector<Row> rows_;
  std::map<std::string, FieldEditor*> byPath_;
  std::set<std::string> collapsed_;
  std::string structure_;
  std::function<const scene::SceneState&()> stateSource_;
  std::function<QWidget*(const std::string&, QWidget*, QWidget*)> decorator_;
  std::function<void(const std::vector<scene::EntityId>&, const std::string&, const QString&)> edited_;
  std::function<void(scene::EntityId)> newTerrain_;
  const scene::SceneState& shown() const { return stateSource_ ? stateSource_() : doc_.state(); }
};

}  // namespace hs::app
