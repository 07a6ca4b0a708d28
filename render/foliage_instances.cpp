#include "render/foliage_instances.h"

#include <algorithm>

#include "foliage/instance.h"

namespace hs::render {

std::vector<InstanceSet> foliageInstanceSets(const scene::SceneState& state, size_t maxInstances) {
  std::vector<InstanceSet> out;
  const foliage::FoliageStore* store = scene::foliageStoreOf(state);
  if (!store || store->cellCount() == 0) return out;
  std::vector<InstanceType> types;
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
  std::vector<foliage::CellKey> keys;
  keys.reserve(store->cellCount());
  for (const auto& [k, c] : store->cells()) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  auto cellSize = [&](const foliage::CellKey& k) {
    size_t n = 0;
    for (const foliage::Run& run : store->cell(k)->runs) n += run.items.size();
    return n;
  };
  for (size_t first = 0; first < keys.size();) {
    InstanceSet set;
    set.types = types;
    // Whole cells while both limits hold (at least one cell a set).
    size_t last = first, instances = 0;
    while (last < keys.size() && last - first < kMaxCellsPerSet) {
      const size_t more = cellSize(keys[last]);
      if (last > first && instances + more > maxInstances) break;
      instances += more;
      ++last;
    }
    set.instances.reserve(instances);
    for (size_t i = first; i < last; ++i) {
      const foliage::CellKey& k = keys[i];
      const uint16_t cell = uint16_t(i - first);
      set.cells.push_back(k.origin());
      for (const foliage::Run& run : store->cell(k)->runs) {
        const foliage::ScaleMode mode = store->type(run.type).scaleMode;
        for (const foliage::PackedInstance& p : run.items) {
          // The store's step grid: q * 2^-10 m is exact in float.
          const glm::vec3 pos(float(p.q[0]) * float(foliage::kStep), float(p.q[1]) * float(foliage::kStep),
                              float(p.q[2]) * float(foliage::kStep));
          const glm::dvec3 s = foliage::unpackScale(mode, p.scale);
          set.instances.push_back(packInstance(pos, glm::quat(foliage::unpackRotation(p.rot)),
                                               glm::vec2(float(s.x), float(s.z)), run.type, cell, p.id));
        }
      }
    }
    out.push_back(std::move(set));
    first = last;
  }
  return out;
}

}  // namespace hs::render
