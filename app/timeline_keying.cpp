#include "app/timeline_keying.h"

#include "app/selection.h"

namespace hs::app {

namespace {

bool pathDriven(const sequencer::Sequence& seq, scene::EntityId id, const std::string& property) {
  const sequencer::Binding* b = seq.findBinding(id);
  return b && b->path && (property == "transform.translation" || property == "transform.rotation");
}

}  // namespace

Keying::Keying(scene::Document& doc, TimelineClock& clock, QObject* parent)
    : QObject(parent), doc_(doc), clock_(clock) {}

bool Keying::keyable(scene::EntityId id, const std::string& fieldPath) const {
  std::string error;
  const auto target = scene::animationTarget(fieldPath, error);
  return target && doc_.state().find(id) && !pathDriven(doc_.state().sequence, id, target->property);
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
    const scene::Entity* e = shown.find(id);
    if (!e || !keyable(id, fieldPath)) continue;
    if (auto v = scene::currentKeyValue(*e, *target)) keys.push_back({id, *target, *v});
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
      const scene::Entity* e = s.find(id);
      if (!e || !keyable(id, path)) continue;
      if (!clock_.autoKey() && !scene::isAnimated(s.sequence, id, target->property)) continue;
      if (auto v = scene::currentKeyValue(*e, *target)) keys.push_back({id, *target, *v});
    }
  }
  if (!keys.empty()) scene::ops::setKeys(doc_, keys, clock_.time(), std::nullopt, "Auto key", mergeKey);
}

KeyButton::KeyButton(Keying& keying, Selection& selection, TimelineClock& clock, std::string fieldPath, QWidget* parent)
    : QToolButton(parent), keying_(keying), selection_(selection), path_(std::move(fieldPath)) {
  setObjectName("key_" + QString::fromStdString(path_));
  setAutoRaise(true);
  setFixedWidth(22);
  setFocusPolicy(Qt::NoFocus);
  connect(this, &QToolButton::clicked, this, [this] {
    if (state_ == Keying::KeyState::KeyHere) keying_.removeKeyHere(selection_.ids(), path_);
    else keying_.keyField(selection_.ids(), path_);
  });
  connect(&clock, &TimelineClock::stateChanged, this, &KeyButton::refresh);
  refresh();
}

void KeyButton::refresh() {
  state_ = keying_.state(selection_.primary(), path_);
  const bool can = keying_.keyable(selection_.primary(), path_);
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
  if (!can) setToolTip("Driven by the camera path (edit the path's keys in the timeline)");
}

}  // namespace hs::app
