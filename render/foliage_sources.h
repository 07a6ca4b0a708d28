#pragma once
// The renderer's instanced sources for the document's foliage
// (foliage_instances.h): rebuilt when the store's revision, the store
// itself or the mesh assets its types name change, and kept across frames
// otherwise (their instance buffers persist in the frame graph's pool, so a
// frame without an edit uploads nothing). GPU culling (the compute passes of
// instanced_source.h). Include only inside render/.
#include <memory>
#include <vector>

#include "render/instanced_source.h"
#include "scene/scene_state.h"

namespace hs::render {

class FoliageSources {
 public:
  // The sources for `state`'s foliage (empty: none), brought up to date.
  const std::vector<std::shared_ptr<InstancedSource>>& update(const scene::SceneState& state);

 private:
  const scene::FoliageData* data_ = nullptr;
  uint64_t revision_ = 0;
  std::vector<scene::AssetId> meshes_;  // per type, what its mesh name found
  std::vector<std::shared_ptr<InstancedSource>> sources_;
};

}  // namespace hs::render
