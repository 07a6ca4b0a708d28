#pragma once
// The scene's visible terrains as a draw source (draw_source.h): CDLOD
// patches chosen per frame from the LOD view (terrain_pass.h), drawn in a
// lit pass of their own ("terrain", after the meshes), into shadow views
// culled against the view's volume, and into the id pass (terrain i gets
// pickBase + i). Terrains are opaque: no transparency variants. Include
// only inside render/.
#include "render/draw_source.h"
#include "render/render_world.h"

namespace hs::render {

class TerrainSource final : public DrawSource {
 public:
  explicit TerrainSource(const RenderWorld& world) : world_(world) {}
  std::string ownPass() const override { return "terrain"; }
  bool has(DrawVariant variant, SurfaceSet surfaces) const override {
    return !world_.terrains.empty() && (variant != DrawVariant::Surface || surfaces == SurfaceSet::Opaque);
  }
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override;
  uint32_t pickIds() const override { return uint32_t(world_.terrains.size()); }
  PickedItem picked(uint32_t k) const override { return {world_.terrains[k], UINT32_MAX}; }

 private:
  const RenderWorld& world_;
};

}  // namespace hs::render
