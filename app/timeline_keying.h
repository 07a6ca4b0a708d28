#pragma once
// Keys from the editor's fields: the key buttons beside each animatable
// field of the property panel (Blender's dot), and keys that follow edits.
// An edit of a property that is already animated sets a key at the current
// frame (otherwise the animation would override the edit at once); with
// Auto Key on, every animatable edit does. The key joins the edit's undo
// step (the same merge key), so one Ctrl+Z takes both back.
#include <functional>
#include <string>
#include <vector>

#include <QObject>
#include <QString>
#include <QToolButton>

#include "app/timeline_clock.h"
#include "scene/document.h"
#include "scene/sequence_edits.h"

namespace hs::app {

class Selection;

class Keying : public QObject {
  Q_OBJECT
 public:
  Keying(scene::Document& doc, TimelineClock& clock, QObject* parent = nullptr);

  enum class KeyState { NotAnimated, Animated, KeyHere };
  // The state of `fieldPath` ("transform.rotation_deg" counts as the
  // rotation track) of the entity at the current frame. Here and below an
  // id may also be a material's or the settings' binding target
  // (scene/object_tracks.h) with a "material.*" / "settings.*" path.
  KeyState state(scene::EntityId id, const std::string& fieldPath) const;
  // Path-driven translation and rotation are not keyed: the path decides them.
  bool keyable(scene::EntityId id, const std::string& fieldPath) const;

  // Keys the field of each entity (that has it) at the current frame with
  // the value it shows now. One undo step.
  bool keyField(const std::vector<scene::EntityId>& ids, const std::string& fieldPath);
  // Removes the keys of the field at the current frame. One undo step.
  bool removeKeyHere(const std::vector<scene::EntityId>& ids, const std::string& fieldPath);
  // After an edit of fields of entities, pushed with `mergeKey`: keys the
  // edited values where the field is animated or Auto Key is on.
  void afterEdit(const std::vector<scene::EntityId>& ids, const std::vector<std::string>& fieldPaths,
                 const QString& mergeKey);

 private:
  scene::Document& doc_;
  TimelineClock& clock_;
};

// The key button of one field: ◇ not animated, ◇ (amber) animated, ◆ keyed
// at this frame. A click keys the selection's field at the current frame, or
// removes the key when there is one here.
class KeyButton : public QToolButton {
  Q_OBJECT
 public:
  // What a click keys: the selected entities, or (the Materials panel, the
  // Scene Settings dock) a material or the settings as binding targets
  // (scene/object_tracks.h); the last one (the primary) decides what the button shows.
  using TargetsFn = std::function<std::vector<uint64_t>()>;
  KeyButton(Keying& keying, Selection& selection, TimelineClock& clock, std::string fieldPath,
            QWidget* parent = nullptr);
  KeyButton(Keying& keying, TargetsFn targets, TimelineClock& clock, std::string fieldPath,
            QWidget* parent = nullptr);
  void refresh();
  Keying::KeyState keyState() const { return state_; }

 private:
  Keying& keying_;
  TargetsFn targets_;
  std::string path_;
  Keying::KeyState state_ = Keying::KeyState::NotAnimated;
};

}  // namespace hs::app
