#include "app/timeline_actions.h"

#include <QMenu>

#include "scene/sequence_edits.h"

namespace hs::app {

namespace {
int gestureCounter = 0;
}

TimelineActions::TimelineActions(scene::Document& doc, TimelineClock& clock, KeySelection& keys, QObject* parent)
    : QObject(parent), doc_(doc), clock_(clock), keys_(keys) {}

QString TimelineActions::newGestureKey() { return QString("timeline-%1").arg(++gestureCounter); }

bool TimelineActions::applyGesture(const sequencer::Sequence& edited, const QString& text, const QString& gestureKey) {
  return scene::ops::replaceSequence(doc_, edited, text, gestureKey);
}

bool TimelineActions::deleteSelected() {
  const std::vector<sequencer::KeyRef> refs = keys_.keys();
  keys_.clear();
  return scene::ops::removeKeys(doc_, refs);
}

void TimelineActions::copySelected() {
  if (!keys_.empty()) clipboard_ = sequencer::copyKeys(doc_.state().sequence, keys_.keys());
}

bool TimelineActions::paste() {
  if (clipboard_.empty()) return false;
  sequencer::Sequence s = doc_.state().sequence;
  const std::vector<sequencer::KeyRef> pasted = sequencer::pasteKeys(s, clipboard_, clock_.time());
  if (!scene::ops::replaceSequence(doc_, s, pasted.size() == 1 ? QString("Paste key") : QString("Paste %1 keys").arg(pasted.size())))
    return false;
  keys_.set(pasted);
  return true;
}

bool TimelineActions::setShape(const sequencer::KeyShape& shape) {
  sequencer::Sequence s = doc_.state().sequence;
  if (sequencer::setKeyShape(s, keys_.keys(), shape) == 0) return false;
  return scene::ops::replaceSequence(doc_, s, "Key interpolation");
}

void TimelineActions::beginMove() {
  if (keys_.empty()) return;
  moving_ = true;
  moveStart_ = doc_.state().sequence;
  moveKeys_ = keys_.keys();
  moveKey_ = newGestureKey();
}

void TimelineActions::moveBy(double seconds) {
  if (!moving_) return;
  sequencer::Sequence s = moveStart_;
  const std::vector<sequencer::KeyRef> moved = sequencer::moveKeysSnapped(s, moveKeys_, seconds, s.rate);
  scene::ops::replaceSequence(doc_, s, moveKeys_.size() == 1 ? QString("Move key") : QString("Move %1 keys").arg(moveKeys_.size()),
                              moveKey_);
  keys_.set(moved);
}

void TimelineActions::endMove() { moving_ = false; }

void TimelineActions::cancelMove() {
  if (!moving_) return;
  // Back to the start under the same key: the drag's undo step then holds
  // no change and disappears.
  scene::ops::replaceSequence(doc_, moveStart_, "Move keys", moveKey_);
  keys_.set(moveKeys_);
  moving_ = false;
}

QMenu* TimelineActions::contextMenu(QWidget* parent) {
  auto* menu = new QMenu(parent);
  const bool any = !keys_.empty();
  QMenu* interp = menu->addMenu("&Interpolation");
  for (auto [name, i] : {std::pair{"&Constant", sequencer::Interpolation::Constant},
                         std::pair{"&Linear", sequencer::Interpolation::Linear},
                         std::pair{"C&ubic", sequencer::Interpolation::Cubic}})
    interp->addAction(name, this, [this, i] { setShape({i, std::nullopt, std::nullopt}); })->setEnabled(any);
  QMenu* tangents = menu->addMenu("&Tangents");
  for (auto [name, m] : {std::pair{"&Auto (clamped, no overshoot)", sequencer::TangentMode::Auto},
                         std::pair{"&User (one slope)", sequencer::TangentMode::User},
                         std::pair{"&Broken (in and out apart)", sequencer::TangentMode::Broken}})
    tangents->addAction(name, this, [this, m] { setShape({std::nullopt, m, std::nullopt}); })->setEnabled(any);
  QMenu* ease = menu->addMenu("&Ease");
  for (auto [name, e] : {std::pair{"&None", sequencer::Ease::None}, std::pair{"&In", sequencer::Ease::In},
                         std::pair{"&Out", sequencer::Ease::Out}, std::pair{"In && Out", sequencer::Ease::InOut}})
    ease->addAction(name, this, [this, e] { setShape({std::nullopt, std::nullopt, e}); })->setEnabled(any);
  menu->addSeparator();
  auto item = [&](const char* text, QKeySequence::StandardKey key, bool enabled, auto fn) {
    QAction* a = menu->addAction(text, this, fn);
    a->setShortcut(key);  // shown in the menu; the views handle the keys themselves
    a->setEnabled(enabled);
  };
  item("&Copy", QKeySequence::Copy, any, [this] { copySelected(); });
  item("&Paste at Playhead", QKeySequence::Paste, hasClipboard(), [this] { paste(); });
  item("&Delete", QKeySequence::Delete, any, [this] { deleteSelected(); });
  return menu;
}

}  // namespace hs::app
