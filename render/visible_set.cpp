#include "render/visible_set.h"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>

#include "render/gpu_mesh_cache.h"
#include "render/mesh_lod.h"

namespace hs::render {
namespace {

// Appends the draw of `inst` at its chosen level.
uint32_t addDraw(VisibleSet& set, const MeshInstanceRef& inst, InstanceBounds& b, GpuMeshCache& cache) {
  const GpuMesh* g = cache.get(*inst.asset);
  if (b.lodLevel > 0)
    if (const GpuMesh* coarser = cache.get(*inst.asset, b.lodLevel)) g = coarser;
  const glm::dmat4& w = inst.world;
  // Relative to the frame origin, formed in double (DESIGN.md).
  glm::dmat4 rel = w;
  rel[3] = glm::dvec4(glm::dvec3(w[3]) - set.origin, 1.0);
  GpuObject o;
  o.model = glm::mat4(rel);
  o.normalMatrix = glm::mat4(glm::mat3(glm::inverseTranspose(glm::dmat3(w))));
  o.tint = glm::vec4(inst.tint, 1.0f);
  b.draw = int32_t(set.draws.size());
  set.draws.push_back({uint32_t(set.objects.size()), g, inst.asset});
  set.objects.push_back(o);
  set.entities.push_back(inst.entity);
  if (set.byOtherSource.size() < set.draws.size()) set.byOtherSource.resize(set.draws.size(), 0);
  return uint32_t(b.draw);
}

}  // namespace

VisibleSet buildVisibleSet(const RenderWorld& world, GpuMeshCache& cache, const std::vector<RenderView>& views,
                           const RenderView* lodView, double lodErrorPixels) {
  VisibleSet set;
  if (views.empty()) return set;
  const RenderView& lv = lodView ? *lodView : views.front();
  set.origin = lv.eye;
  std::vector<Frustum> frusta;
  for (const RenderView& v : views) frusta.push_back(frustumOf(v));
  set.instances.resize(world.meshes.size());
  for (size_t i = 0; i < world.meshes.size(); ++i) {
    const MeshInstanceRef& inst = world.meshes[i];
    InstanceBounds& b = set.instances[i];
    b.radius = -1.0;  // no data: never drawn
    const GpuMesh* g = cache.get(*inst.asset);
    if (!g) continue;
    const glm::dmat4& w = inst.world;
    const glm::dvec3 centre = glm::dvec3(w * glm::dvec4(glm::dvec3(g->bounds.center()), 1.0));
    const double maxScale = std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])),
                                      glm::length(glm::dvec3(w[2]))});
    b.centre = centre - set.origin;
    b.radius = double(g->bounds.radius()) * maxScale;
    // The coarsest LOD within the scene's pixel bound (mesh_lod.h), as seen
    // from the LOD view: the same level in every view, shadow views too,
    // so a mesh shadows itself with its own triangles.
    if (!inst.asset->lods.empty())
      b.lodLevel = chooseMeshLod(inst.asset->lodErrors(), centre - lv.eye, double(g->bounds.radius()), maxScale, lv,
                                 lodErrorPixels)
                       .level;
    bool inside = false;
    for (size_t v = 0; v < views.size() && !inside; ++v)
      inside = frusta[v].intersectsSphere(centre - views[v].eye, b.radius);
    if (!inside) {
      ++set.culled;
      continue;
    }
    if (b.lodLevel > 0) ++set.coarser;
    addDraw(set, inst, b, cache);
  }
  set.inView = set.draws.size();
  set.byOtherSource.assign(set.inView, 0);
  return set;
}

uint32_t addCasterDraw(VisibleSet& set, const RenderWorld& world, GpuMeshCache& cache, size_t instance) {
  InstanceBounds& b = set.instances[instance];
  if (b.draw >= 0) return uint32_t(b.draw);
  return addDraw(set, world.meshes[instance], b, cache);
}

void forEachInViewCorner(const VisibleSet& set, const std::function<void(const glm::dvec3&)>& f) {
  for (size_t d = 0; d < set.inView; ++d) {
    const DrawItem& it = set.draws[d];
    const glm::dmat4 m(set.objects[it.object].model);
    const mesh::Bounds& b = it.mesh->bounds;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 local(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z);
      f(set.origin + glm::dvec3(m * glm::dvec4(local, 1.0)));
    }
  }
}

}  // namespace hs::render
