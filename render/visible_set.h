#pragma once
// The mesh draws of one frame, built once and shared by every view that
// draws it (DESIGN.md): both eyes of a stereo pair, the mono LOD view, and
// the shadow views. An instance is drawn in the camera views if it is in
// any view's frustum; its level of detail is chosen from the LOD view
// alone, so both eyes and every shadow view draw the same level. Object
// data (matrices relative to the frame origin, tints) is laid out here for
// one upload per frame.
#include <functional>
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

// Every mesh instance of the world with what culling needs, computed once:
// the shadow views cull these without choosing bounds or levels again.
struct InstanceBounds {
  glm::dvec3 centre{0.0};  // frame-relative
  double radius = 0.0;
  int lodLevel = 0;        // chosen from the LOD view (0: full detail)
  int32_t draw = -1;       // its draw in VisibleSet::draws, once it has one
};

struct VisibleSet {
  glm::dvec3 origin{0.0};               // the frame origin: the LOD view's eye
  // [0, inView): instances in a camera view; after them, instances that
  // are only shadow casters (added by shadow views, addCasterDraw).
  std::vector<DrawItem> draws;
  size_t inView = 0;
  std::vector<GpuObject> objects;        // one per draw
  std::vector<scene::EntityId> entities; // one per draw (picking)
  std::vector<InstanceBounds> instances; // one per RenderWorld::meshes entry
  // Per draw: drawn by another source (a mesh with a cluster hierarchy,
  // cluster_source.h), which the mesh source then leaves out.
  std::vector<uint8_t> byOtherSource;
  size_t culled = 0;                     // instances outside every view
  size_t coarser = 0;                    // drawn in view at a LOD level above 0
};

// `views` are the views that will draw the set; `lodView` chooses levels
// (usually the frame's mono camera; views[0] when null).
VisibleSet buildVisibleSet(const RenderWorld& world, GpuMeshCache& cache, const std::vector<RenderView>& views,
                           const RenderView* lodView, double lodErrorPixels);

// The world-space corners (double) of every in-view draw's mesh box, eight
// a draw, each handed to `f`: the depth of field's nearest depth and the
// mesh particles' lowest receiver read them.
void forEachInViewCorner(const VisibleSet& set, const std::function<void(const glm::dvec3&)>& f);

// The draw of world.meshes[instance], made (a caster outside every view) if
// it has none yet; its index in set.draws.
uint32_t addCasterDraw(VisibleSet& set, const RenderWorld& world, GpuMeshCache& cache, size_t instance);

}  // namespace hs::render
