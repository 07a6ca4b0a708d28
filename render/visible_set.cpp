#include "render/visible_set.h"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>

#include "render/gpu_mesh_cache.h"
#include "render/mesh_lod.h"

namespace hs::render {

VisibleSet buildVisibleSet(const RenderWorld& world, GpuMeshCache& cache, const std::vector<RenderView>& views,
                           const RenderView* lodView, double lodErrorPixels) {
  VisibleSet set;
  if (views.empty()) return set;
  const RenderView& lv = lodView ? *lodView : views.front();
  set.origin = lv.eye;
  std::vector<Frustum> frusta;
  for (const RenderView& v : views) frusta.push_back(frustumOf(v));
  for (const MeshInstanceRef& inst : world.meshes) {
    const GpuMesh* g = cache.get(*inst.asset);
    if (!g) continue;
    const glm::dmat4& w = inst.world;
    const glm::dvec3 centre = glm::dvec3(w * glm::dvec4(glm::dvec3(g->bounds.center()), 1.0));
    const double maxScale = std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])),
                                      glm::length(glm::dvec3(w[2]))});
    const double radius = double(g->bounds.radius()) * maxScale;
    bool inside = false;
    for (size_t i = 0; i < views.size() && !inside; ++i)
      inside = frusta[i].intersectsSphere(centre - views[i].eye, radius);
    if (!inside) {
      ++set.culled;
      continue;
    }
    // The coarsest LOD within the scene's pixel bound (mesh_lod.h), as seen
    // from the LOD view.
    if (!inst.asset->lods.empty()) {
      const MeshLodChoice lod = chooseMeshLod(inst.asset->lodErrors(), centre - lv.eye, double(g->bounds.radius()),
                                              maxScale, lv, lodErrorPixels);
      if (lod.level > 0) {
        if (const GpuMesh* coarser = cache.get(*inst.asset, lod.level)) g = coarser;
        ++set.coarser;
      }
    }
    // Relative to the frame origin, formed in double (DESIGN.md).
    glm::dmat4 rel = w;
    rel[3] = glm::dvec4(glm::dvec3(w[3]) - set.origin, 1.0);
    GpuObject o;
    o.model = glm::mat4(rel);
    o.normalMatrix = glm::mat4(glm::mat3(glm::inverseTranspose(glm::dmat3(w))));
    o.tint = glm::vec4(inst.tint, 1.0f);
    set.draws.push_back({uint32_t(set.objects.size()), g, inst.asset});
    set.objects.push_back(o);
    set.entities.push_back(inst.entity);
  }
  return set;
}

}  // namespace hs::render
