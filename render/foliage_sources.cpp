#include "render/foliage_sources.h"

#include "render/foliage_instances.h"

namespace hs::render {

const std::vector<std::shared_ptr<InstancedSource>>& FoliageSources::update(const scene::SceneState& state) {
  const scene::FoliageData* data = state.foliage.get();
  std::vector<scene::AssetId> meshes;
  if (data)
    for (const foliage::FoliageType& t : data->store().types()) meshes.push_back(scene::foliageTypeAsset(state, t));
  if (data == data_ && (!data || data->revision() == revision_) && meshes == meshes_) return sources_;
  data_ = data;
  revision_ = data ? data->revision() : 0;
  meshes_ = std::move(meshes);
  std::vector<InstanceSet> sets = foliageInstanceSets(state);
  sources_.resize(sets.size());
  for (size_t i = 0; i < sets.size(); ++i) {
    // A source keeps its pool buffer's name across updates, so an edit
    // re-uploads into the same buffer instead of allocating another.
    if (!sources_[i])
      sources_[i] = std::make_shared<InstancedSource>("foliage" + (i ? std::to_string(i) : std::string()),
                                                      InstancedSource::Culling::Gpu);
    sources_[i]->setInstances(std::move(sets[i]));
  }
  return sources_;
}

}  // namespace hs::render
