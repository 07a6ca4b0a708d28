#include "render/foliage_instances.h"

#include <algorithm>

namespace hs::render {
namespace {

// Cell `cell`'s instances packed at `out` (as many as it has).
void packCell(const foliage::FoliageStore& store, const foliage::Cell& c, uint16_t cell, GpuInstance* out) {
  for (const foliage::Run& run : c.runs) {
    const foliage::ScaleMode mode = store.type(run.type).scaleMode;
    for (const foliage::PackedInstance& p : run.items) {
      // The store's step grid: q * 2^-10 m is exact in float.
      const glm::vec3 pos(float(p.q[0]) * float(foliage::kStep), float(p.q[1]) * float(foliage::kStep),
                          float(p.q[2]) * float(foliage::kStep));
      const glm::dvec3 s = foliage::unpackScale(mode, p.scale);
      *out++ = packInstance(pos, glm::quat(foliage::unpackRotation(p.rot)), glm::vec2(float(s.x), float(s.z)),
                            run.type, cell, p.id);
    }
  }
}

// The sets, each cell given room(count) places; `slots` (may be null)
// gets each cell's.
std::vector<InstanceSet> buildSets(const scene::SceneState& state, size_t maxInstances,
                                   size_t (*room)(size_t), CellSlots* slots, std::vector<size_t>* tails) {
  std::vector<InstanceSet> out;
  if (slots) slots->clear();
  if (tails) tails->clear();
  const foliage::FoliageStore* store = scene::foliageStoreOf(state);
  if (!store || store->cellCount() == 0) return out;
  const std::vector<InstanceType> types = foliageInstanceTypes(state);
  std::vector<foliage::CellKey> keys;
  keys.reserve(store->cellCount());
  for (const auto& [k, c] : store->cells()) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  for (size_t first = 0; first < keys.size();) {
    InstanceSet set;
    set.types = types;
    // Whole cells while both limits hold (at least one cell a set).
    size_t last = first, places = 0;
    while (last < keys.size() && last - first < kMaxCellsPerSet) {
      const size_t more = room(store->cell(keys[last])->count());
      if (last > first && places + more > maxInstances) break;
      places += more;
      ++last;
    }
    set.instances.assign(places + (tails ? setTail(places, maxInstances) : 0), kSpareInstance);
    if (tails) tails->push_back(places);
    size_t at = 0;
    for (size_t i = first; i < last; ++i) {
      const foliage::CellKey& k = keys[i];
      const foliage::Cell& c = *store->cell(k);
      const uint16_t cell = uint16_t(i - first);
      const size_t count = c.count(), r = room(count);
      set.cells.push_back(k.origin());
      packCell(*store, c, cell, set.instances.data() + at);
      if (slots) (*slots)[k] = {out.size(), cell, at, count, r, store->cellRevision(k)};
      at += r;
    }
    out.push_back(std::move(set));
    first = last;
  }
  return out;
}

size_t tight(size_t count) { return count; }

}  // namespace

std::vector<InstanceType> foliageInstanceTypes(const scene::SceneState& state) {
  std::vector<InstanceType> types;
  const foliage::FoliageStore* store = scene::foliageStoreOf(state);
  if (!store) return types;
  for (const foliage::FoliageType& t : store->types()) {
    InstanceType it;
    it.mesh = scene::foliageTypeAsset(state, t);
    it.cullDistance = float(t.cullDistance);
    it.fadeLength = float(std::min(t.fadeLength, t.cullDistance));
    it.windResponse = float(t.windResponse);
    it.castShadows = t.castShadows;
    it.impostor = t.impostor;
    types.push_back(it);
  }
  return types;
}

size_t cellRoom(size_t count) { return count + count / 4 + 16; }

size_t setTail(size_t places, size_t maxInstances) {
  return places >= maxInstances ? 0 : std::min(places / 8 + 4096, maxInstances - places);
}

std::vector<InstanceSet> foliageInstanceSets(const scene::SceneState& state, size_t maxInstances) {
  return buildSets(state, maxInstances, tight, nullptr, nullptr);
}

std::vector<InstanceSet> foliagePagedSets(const scene::SceneState& state, CellSlots& slots,
                                          std::vector<size_t>& tails, size_t maxInstances) {
  return buildSets(state, maxInstances, cellRoom, &slots, &tails);
}

bool repackCell(const foliage::FoliageStore& store, const foliage::CellKey& key, CellSlot& slot,
                std::vector<GpuInstance>& out) {
  const foliage::Cell* c = store.cell(key);
  const size_t count = c ? c->count() : 0;
  if (count > slot.room) return false;
  out.assign(slot.room, kSpareInstance);
  if (c) packCell(store, *c, slot.cell, out.data());
  slot.count = count;
  slot.revision = store.cellRevision(key);
  return true;
}

}  // namespace hs::render
