#include "app/timeline_selection.h"

#include <algorithm>

namespace hs::app {

bool KeySelection::contains(const sequencer::KeyRef& k) const {
  return std::binary_search(keys_.begin(), keys_.end(), k);
}

void KeySelection::set(std::vector<sequencer::KeyRef> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (keys == keys_) return;
  keys_ = std::move(keys);
  emit changed();
}

void KeySelection::add(const std::vector<sequencer::KeyRef>& keys) {
  std::vector<sequencer::KeyRef> all = keys_;
  all.insert(all.end(), keys.begin(), keys.end());
  set(std::move(all));
}

void KeySelection::toggle(const sequencer::KeyRef& key) {
  std::vector<sequencer::KeyRef> all = keys_;
  const auto it = std::find(all.begin(), all.end(), key);
  if (it == all.end()) all.push_back(key);
  else all.erase(it);
  set(std::move(all));
}

void KeySelection::prune(const sequencer::Sequence& sequence) {
  std::vector<sequencer::KeyRef> kept;
  for (const sequencer::KeyRef& k : keys_)
    if (sequencer::keyExists(sequence, k)) kept.push_back(k);
  set(std::move(kept));
}

}  // namespace hs::app
