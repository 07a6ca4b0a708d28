#include "app/selection.h"

#include <algorithm>

#include "scene/scene_state.h"

namespace hs::app {

bool Selection::contains(EntityId id) const { return std::find(ids_.begin(), ids_.end(), id) != ids_.end(); }

void Selection::set(std::vector<EntityId> ids) {
  std::vector<EntityId> unique;
  for (EntityId id : ids)
    if (id != scene::kNoEntity && std::find(unique.begin(), unique.end(), id) == unique.end()) unique.push_back(id);
  if (unique == ids_) return;
  ids_ = std::move(unique);
  emit changed();
}

void Selection::select(EntityId id) { set(id == scene::kNoEntity ? std::vector<EntityId>{} : std::vector<EntityId>{id}); }

void Selection::add(EntityId id) {
  std::vector<EntityId> next = ids_;
  std::erase(next, id);
  next.push_back(id);
  set(std::move(next));
}

void Selection::toggle(EntityId id) {
  if (contains(id)) {
    std::vector<EntityId> next = ids_;
    std::erase(next, id);
    set(std::move(next));
  } else {
    add(id);
  }
}

void Selection::prune(const scene::SceneState& state) {
  std::vector<EntityId> next;
  for (EntityId id : ids_)
    if (state.find(id)) next.push_back(id);
  set(std::move(next));
}

}  // namespace hs::app
