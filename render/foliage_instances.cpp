#include "render/foliage_instances.h"

#include <algorithm>

#include "foliage/instance.h"

namespace hs::render {

std::vector<InstanceSet> foliageInstanceSets(const scene::SceneState& state) {
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
    types.push_back(it);
  }
  std::vector<foliage::CellKey> keys;
  keys.reserve(store->cellCount());
  for (const auto& [k, c] : store->cells()) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  for (size_t first = 0; first < keys.size(); first += kMaxCellsPerSet) {
    InstanceSet set;
    set.types = types;
    const size_t last = std::min(keys.size(), first + kMaxCellsPerSet);
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
  }
  return out;
}

}  // namespace hs::render
