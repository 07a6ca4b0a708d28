#include "render/foliage_sources.h"

#include <algorithm>

namespace hs::render {

const std::vector<std::shared_ptr<InstancedSource>>& FoliageSources::update(const scene::SceneState& state) {
  lastRepacked_ = 0;
  lastRebuilt_ = false;
  const scene::FoliageData* data = state.foliage.get();
  // Types as the sets would have them now (a mesh asset found by name may
  // have been renamed, added or removed without the store changing).
  const std::vector<InstanceType> types = foliageInstanceTypes(state);
  const bool sameSets = data_.lock().get() == data && types == types_;
  if (sameSets && (!data || data->revision() == revision_)) return sources_;
  data_ = state.foliage;
  revision_ = data ? data->revision() : 0;
  if (sameSets && data && !sources_.empty() && repack(data->store())) return sources_;
  types_ = types;
  rebuild(state);
  return sources_;
}

bool FoliageSources::repack(const foliage::FoliageStore& store) {
  // A cell the sets do not have gets a slot from the first tail with room
  // for it (and a cell index to spare): all of them, or a rebuild.
  struct NewCell {
    foliage::CellKey key;
    size_t set, first, room;
  };
  std::vector<NewCell> added;
  std::vector<size_t> tails = tails_;
  std::vector<size_t> cells(sources_.size());
  for (size_t i = 0; i < sources_.size(); ++i) cells[i] = sources_[i]->instances().cells.size();
  for (const auto& [k, c] : store.cells()) {
    if (slots_.count(k)) continue;
    const size_t room = cellRoom(c.count());
    size_t set = 0;
    while (set < sources_.size() &&
           (tails[set] + room > sources_[set]->instances().instances.size() || cells[set] >= kMaxCellsPerSet))
      ++set;
    if (set == sources_.size()) return false;
    added.push_back({k, set, tails[set], room});
    tails[set] += room;
    ++cells[set];
  }
  for (const NewCell& n : added) {
    const uint16_t cell = sources_[n.set]->addCell(n.key.origin());
    // No revision yet: packed below with the changed cells.
    slots_[n.key] = {n.set, cell, n.first, 0, n.room, UINT64_MAX};
  }
  tails_ = std::move(tails);
  struct Change {
    foliage::CellKey key;
    CellSlot* slot;
  };
  std::vector<Change> changed;
  for (auto& [k, slot] : slots_)
    if (store.cellRevision(k) != slot.revision) {
      const foliage::Cell* c = store.cell(k);
      if (c && c->count() > slot.room) return false;  // grown past its room: rebuild
      changed.push_back({k, &slot});
    }
  std::vector<GpuInstance> packed;
  for (const Change& ch : changed) {
    repackCell(store, ch.key, *ch.slot, packed);
    sources_[ch.slot->set]->updateInstances(ch.slot->first, packed.data(), packed.size());
  }
  lastRepacked_ = changed.size();
  return true;
}

void FoliageSources::rebuild(const scene::SceneState& state) {
  lastRebuilt_ = true;
  std::vector<InstanceSet> sets = foliagePagedSets(state, slots_, tails_);
  sources_.resize(sets.size());
  for (size_t i = 0; i < sets.size(); ++i) {
    // A source keeps its pool buffer's name across updates, so a rebuild
    // uploads into the same buffer instead of allocating another.
    if (!sources_[i])
      sources_[i] = std::make_shared<InstancedSource>("foliage" + (i ? std::to_string(i) : std::string()),
                                                      InstancedSource::Culling::Gpu);
    sources_[i]->setInstances(std::move(sets[i]));
  }
}

}  // namespace hs::render
