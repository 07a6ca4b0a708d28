#include "app/timeline_keying.h"

#include "app/selection.h"
#include "scene/object_tracks.h"

namespace hs::app {

namespace {

bool pathDriven(const sequencer::Sequence& seq, scene::EntityId id, const std::string& property) {
  const sequencer::Binding* b = seq.findBinding(id);
  return b && b->path && (property == "transform.translation" || property == "transform.rotation");
}

// The value a key takes now: an entity's field, or a material's or the
// settings' (object_tracks.h), as the timeline shows them at this frame.
std::optional<sequencer::PropertyValue> shownValue(const scene::SceneState& shown, uint64_t id,
                                                   const scene::AnimTarget& target) {
  if (!sequencer::isEntityTarget(id)) return scene::currentObjectValue(shown, id, target.property);
  const scene::Entity* e = shown.find(id);
  return e ? scene::currentKeyValue(*e, target) : std::nullopt;
}

}  // namespace

Keying::Keying(scene::Document& doc, TimelineClock& clock, QObject* parent)
    : QObject(parent), doc_(doc), clock_(clock) {}

bool Keying::keyable(scene::EntityId id, const std::string& fieldPath) const {
  std::string error;
  const auto target = scene::animationTarget(fieldPath, error);
  return target && scene::targetExists(doc_.state(), id) && scene::propertyFitsTarget(id, target->property) &&
         !pathDriven(doc_.state().sequence, id, target->property);
}

Keying::KeyState Keying::state(scene::EntityId id, const std::string& fieldPath) const {
  const std::string property = scene::trackPropertyForField(fieldPath);
  const sequencer::Sequence& seq = doc_.state().sequence;
  if (!scene::isAnimated(seq, id, property)) return KeyState::NotAnimated;
  return scene::hasKeyAt(seq, id, property, clock_.time()) ? KeyState::KeyHere : KeyState::Animated;
}

bool Keying::keyField(const std::vector<scene::EntityId>& ids, const std::string& fieldPath) {
  std::string error;
  const auto target = scene::animationTarget(fieldPath, error);
  if (!target) return false;
  const scene::SceneState& shown = clock_.state();
  std::vector<scene::ops::KeyToSet> keys;
  for (scene::EntityId id : ids) {
    if (!keyable(id, fieldPath)) continue;
    if (auto v = shownValue(shown, id, *target)) keys.push_back({id, *target, *v});
  }
  return scene::ops::setKeys(doc_, keys, clock_.time(), std::nullopt,
                             QString("Key %1").arg(QString::fromStdString(fieldPath)));
}

bool Keying::removeKeyHere(const std::vector<scene::EntityId>& ids, const std::string& fieldPath) {
  const std::string property = scene::trackPropertyForField(fieldPath);
  const sequencer::Sequence& seq = doc_.state().sequence;
  std::vector<sequencer::KeyRef> refs;
  for (scene::EntityId id : ids) {
    const std::vector<double> times = sequencer::keyTimes(seq, id, property);
    for (size_t i = 0; i < times.size(); ++i)
      if (sequencer::sameKeyTime(times[i], clock_.time())) refs.push_back({id, property, i});
  }
  return scene::ops::removeKeys(doc_, refs);
}

void Keying::afterEdit(const std::vector<scene::EntityId>& ids, const std::vector<std::string>& fieldPaths,
                       const QString& mergeKey) {
  const scene::SceneState& s = doc_.state();  // the edited (base) values
  std::vector<scene::ops::KeyToSet> keys;
  for (const std::string& path : fieldPaths) {
    std::string error;
    const auto target = scene::animationTarget(path, error);
    if (!target) continue;
    for (scene::EntityId id : ids) {
      if (!keyable(id, path)) continue;
      if (!clock_.autoKey() && !scene::isAnimated(s.sequence, id, target->property)) continue;
      if (auto v = shownValue(s, id, *target)) keys.push_back({id, *target, *v});
    }
  }
  if (!keys.empty()) scene::ops::setKeys(doc_, keys, clock_.time(), std::nullopt, "Auto key", mergeKey);
}

KeyButton::KeyButton(Keying& keying, Selection& selection, TimelineClock& clock, std::string fieldPath, QWidget* parent)
    : KeyButton(keying, [&selection] { return selection.ids(); }, clock, std::move(fieldPath), parent) {}

KeyButton::KeyButton(Keying& keying, TargetsFn targets, TimelineClock& clock, std::string fieldPath, QWidget* parent)
    : QToolButton(parent), keying_(keying), targets_(std::move(targets)), path_(std::move(fieldPath)) {
  setObjectName("key_" + QString::fromStdString(path_));
  setAutoRaise(true);
  setFixedWidth(22);
  setFocusPolicy(Qt::NoFocus);
  connect(this, &QToolButton::clicked, this, [this] {
    if (state_ == Keying::KeyState::KeyHere) keying_.removeKeyHere(targets_(), path_);
    else keying_.keyField(targets_(), path_);
  });
  connect(&clock, &TimelineClock::stateChanged, this, &KeyButton::refresh);
  refresh();
}

void KeyButton::refresh() {
  const std::vector<uint64_t> targets = targets_();
  const uint64_t primary = targets.empty() ? scene::kNoEntity : targets.back();  // as Selection::primary
  state_ = keying_.state(primary, path_);
  const bool can = keying_.keyable(primary, path_);
  setEnabled(can);
  switch (state_) {
    case Keying::KeyState::NotAnimated:
      setText("◇");
      setStyleSheet("QToolButton { color: #8f9095; }");
      setToolTip("Set a key at the current frame (not animated yet)");
      break;
    case Keying::KeyState::Animated:
      setText("◇");
      setStyleSheet("QToolButton { color: #e0b040; }");
      setToolTip("Animated: set a key at the current frame");
      break;
    case Keying::KeyState::KeyHere:
      setText("◆");
      setStyleSheet("QToolButton { color: #f0a020; }");
      setToolTip("Keyed at this frame: click to remove the key");
      break;
  }
  if (!can && primary != scene::kNoEntity && sequencer::isEntityTarget(primary))
    setToolTip("Driven by the camera path (edit the path's keys in the timeline)");
}

}  // namespace hs::app
