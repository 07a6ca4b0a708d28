#pragma once
// The Lights dock: every light of the scene in one table (name, then each
// field of the "light" component as scene/fields.cpp declares it: type,
// colour, intensity with its unit, lux for a sun and lumens for point and
// spot lights, range, cones, casts_shadows, shadow_resolution), edited with
// the same field editors as the Properties dock (app/field_editors.h)
// through scene::ops::setField (undoable, range-checked). Buttons add a
// sun, a point or a spot light through the editor's Create commands (the
// `addRequested` signal) and delete the selected lights. The table's
// selection is the editor's Selection, so the outliner and the viewport
// follow it and it follows them.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/components.h"
#include "scene/document.h"
#include "scene/fields.h"

class QTableWidget;
class QToolButton;

namespace hs::app {

class FieldEditor;
class KeyButton;
class Keying;
class Selection;
class TimelineClock;

class LightsPanel : public QWidget {
  Q_OBJECT
 public:
  LightsPanel(scene::Document& doc, Selection& selection, QWidget* parent = nullptr);

  // Values shown come from here (the timeline's state at the current frame);
  // without it, the document's.
  void setStateSource(std::function<const scene::SceneState&()> source);
  // Called after each edit with the entity, the field path and the edit's
  // merge key (the timeline's keying joins animated fields to the step).
  void setEditedHook(std::function<void(scene::EntityId, const std::string&, const QString&)> hook);
  // A key button beside each animatable field of each row (it keys that
  // row's light at the timeline's frame), as the Properties dock has.
  void enableKeying(Keying& keying, TimelineClock& clock);
  // The key button of `key` ("intensity") in the row of light `id`; null
  // before enableKeying or for a field that cannot be animated.
  KeyButton* keyButtonFor(scene::EntityId id, const std::string& key) const;

  // The lights in table order (the document's entity order).
  const std::vector<scene::EntityId>& lights() const { return lights_; }
  // The editor of `key` ("intensity") in the row of light `id`; null if none.
  FieldEditor* editorFor(scene::EntityId id, const std::string& key) const;
  // The unit the row of light `id` shows for its intensity ("lx", "lm").
  QString intensityUnit(scene::EntityId id) const;
  QTableWidget* table() const { return table_; }
  QToolButton* addButton(scene::Light::Type type) const;
  QToolButton* deleteButton() const { return delete_; }

  void refreshValues();

 signals:
  // A light of this type should be created (MainWindow::createEntity).
  void addRequested(scene::Light::Type type);
  // A value refused by its field's range or rule, or clamped.
  void problem(const QString& message);

 private:
  void rebuild();
  void selectionToTable();
  void tableToSelection();
  void apply(scene::EntityId id, const scene::EntityField& field, const scene::FieldValue& value, int component,
             const QString& mergeKey);
  const scene::SceneState& shown() const { return stateSource_ ? stateSource_() : doc_.state(); }
  // What decides the table's rows and widgets: the lights and their types.
  std::string structureKey() const;

  scene::Document& doc_;
  Selection& selection_;
  QTableWidget* table_ = nullptr;
  std::map<scene::Light::Type, QToolButton*> add_;
  QToolButton* delete_ = nullptr;
  std::vector<scene::EntityId> lights_;
  std::map<std::pair<scene::EntityId, std::string>, FieldEditor*> editors_;
  std::map<std::pair<scene::EntityId, std::string>, KeyButton*> keyButtons_;
  Keying* keying_ = nullptr;
  TimelineClock* clock_ = nullptr;
  std::string structure_;
  std::function<const scene::SceneState&()> stateSource_;
  std::function<void(scene::EntityId, const std::string&, const QString&)> edited_;
  bool syncing_ = false;
  int editCounter_ = 0;
};

}  // namespace hs::app
