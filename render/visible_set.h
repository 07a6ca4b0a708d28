#pragma once
// The mesh draws of one frame, built once and shared by every view that
// draws it (DESIGN.md): both eyes of a stereo pair, the mono LOD view, and
// later the shadow cascades. An instance is kept if it is in any view's
// frustum; its level of detail is chosen from the LOD view alone, so both
// eyes always draw the same level. Object data (matrices relative to the
// frame origin, tints) is laid out here for one upload per frame.
#include <cstddef>
#include <vector>

#include "render/frame_blocks.h"
#include "render/render_view.h"
#include "render/render_world.h"

namespace hs::render {

struct GpuMesh;
class GpuMeshCache;

struct DrawItem {
  uint32_t object = 0;   // index into VisibleSet::objects
  const GpuMesh* mesh = nullptr;
  const scene::MeshAsset* asset = nullptr;  // its material slots (material_table.h)
};

struct VisibleSet {
  glm::dvec3 origin{0.0};               // the frame origin: the LOD view's eye
  std::vector<DrawItem> draws;
  std::vector<GpuObject> objects;        // one per draw
  std::vector<scene::EntityId> entities; // one per object (picking)
  size_t culled = 0;                     // instances outside every view
  size_t coarser = 0;                    // drawn at a LOD level above 0
};

// `views` are the views that will draw the set; `lodView` chooses levels
// (usually the frame's mono camera; views[0] when null).
VisibleSet buildVisibleSet(const RenderWorld& world, GpuMeshCache& cache, const std::vector<RenderView>& views,
                           const RenderView* lodView, double lodErrorPixels);

}  // namespace hs::render
