#pragma once
// The document's mesh instances as a draw source (draw_source.h): the
// frame's visible set (visible_set.h) drawn from CPU lists, one
// glDrawElementsInstancedBaseInstance per submesh, the instance's object
// index reaching the shaders through the VAOs' attribute 7. Materials come
// from the frame's MaterialTable; shadow views cull the frame's instances
// with the bounds and levels the visible set chose, and an instance outside
// every camera view that casts into one gets a draw of its own
// (addCasterDraw). The transparency key is the object and the primitive
// (shaders/oit_main.glsl oitKey). Include only inside render/.
#include <vector>

#include "render/draw_source.h"
#include "render/visible_set.h"

namespace hs::render {

class GpuMeshCache;
class MaterialTable;

class MeshSource final : public DrawSource {
 public:
  MeshSource(VisibleSet& visible, const RenderWorld& world, GpuMeshCache& cache, const MaterialTable& materials)
      : visible_(visible), world_(world), cache_(cache), materials_(materials) {}

  bool has(DrawVariant variant, SurfaceSet surfaces) const override;
  void cullShadowViews(FrameContext& frame, size_t first, size_t count) override;
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override;
  size_t triangles(SurfaceSet surfaces) const override;
  uint32_t pickIds() const override { return uint32_t(visible_.inView); }
  PickedItem picked(uint32_t k) const override { return {visible_.entities[k], UINT32_MAX}; }

  // The casters of shadow view `v` (indices into VisibleSet::draws).
  const std::vector<uint32_t>& casters(size_t v) const { return casters_[v]; }

 private:
  void drawSurfaceSet(FrameContext& frame, const DrawCall& call) const;
  void drawDepth(FrameContext& frame, const std::vector<uint32_t>& draws) const;
  bool wanted(size_t draw, size_t submesh, SurfaceSet surfaces) const;

  VisibleSet& visible_;
  const RenderWorld& world_;
  GpuMeshCache& cache_;
  const MaterialTable& materials_;  // built after the shadow views culled (their casters have materials too)
  std::vector<std::vector<uint32_t>> casters_;  // per shadow view of the frame
};

}  // namespace hs::render
