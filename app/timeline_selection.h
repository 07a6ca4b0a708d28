#pragma once
// The selected keys of the timeline, shared by the dope sheet and the curve
// view. Keys are named by (entity, property, index); after an edit or an
// undo, references to keys that no longer exist are dropped.
#include <vector>

#include <QObject>

#include "sequencer/key_edit.h"

namespace hs::app {

class KeySelection : public QObject {
  Q_OBJECT
 public:
  explicit KeySelection(QObject* parent = nullptr) : QObject(parent) {}

  const std::vector<sequencer::KeyRef>& keys() const { return keys_; }
  bool empty() const { return keys_.empty(); }
  bool contains(const sequencer::KeyRef& k) const;
  void set(std::vector<sequencer::KeyRef> keys);
  void add(const std::vector<sequencer::KeyRef>& keys);
  void toggle(const sequencer::KeyRef& key);
  void clear() { set({}); }
  void prune(const sequencer::Sequence& sequence);

 signals:
  void changed();

 private:
  std::vector<sequencer::KeyRef> keys_;  // sorted, unique
};

}  // namespace hs::app
