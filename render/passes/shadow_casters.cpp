#include "render/passes/shadow_casters.h"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>

#include "render/gpu_mesh_cache.h"
#include "render/mesh_lod.h"
#include "scene/mesh_materials.h"

namespace hs::render {
namespace {

// The submeshes of `g` (the level drawn) whose document material cuts out
// or is translucent (opacity under 1: drawn by the transparency path).
void findCutouts(const FrameContext& frame, const scene::MeshAsset& asset, const GpuMesh& g, ShadowCaster& c) {
  const mesh::MeshData& base = asset.data ? *asset.data : *g.data;
  const scene::SceneState& state = *frame.world.state;
  std::vector<std::pair<uint32_t, uint32_t>> opaque;
  for (const mesh::Submesh& sm : g.data->submeshes) {
    const size_t slot = scene::materialSlotOf(base, sm);
    const scene::Material* m =
        slot < asset.materialSlots.size() ? state.findMaterial(asset.materialSlots[slot]) : nullptr;
    if (m && (m->alphaCutout || m->opacity < 1.0f)) {
      CutoutPart p{sm.firstIndex, sm.indexCount, 0, m->opacity, m->alphaThreshold, !m->alphaCutout};
      p.texture = frame.res.materials.baseColorTexture(state, *m, g, frame.res.meshes);
      c.cutouts.push_back(p);
    } else {
      opaque.emplace_back(sm.firstIndex, sm.indexCount);
    }
  }
  if (!c.cutouts.empty()) c.opaqueRanges = std::move(opaque);
}

}  // namespace

void gatherShadowCasters(const FrameContext& frame, std::vector<ShadowCaster>& casters,
                         std::vector<GpuObject>& objects) {
  const glm::dvec3 origin = frame.visible.origin;
  for (const MeshInstanceRef& inst : frame.world.meshes) {
    const GpuMesh* g = frame.res.meshes.get(*inst.asset);
    if (!g) continue;
    const glm::dmat4& w = inst.world;
    const glm::dvec3 centre = glm::dvec3(w * glm::dvec4(glm::dvec3(g->bounds.center()), 1.0));
    const double maxScale = std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])),
                                      glm::length(glm::dvec3(w[2]))});
    // The level the views draw (the same choice as visible_set.cpp), so a
    // mesh shadows itself with its own triangles.
    if (!inst.asset->lods.empty()) {
      const MeshLodChoice lod = chooseMeshLod(inst.asset->lodErrors(), centre - frame.lodView.eye,
                                              double(g->bounds.radius()), maxScale, frame.lodView,
                                              frame.settings.meshLodErrorPixels);
      if (lod.level > 0)
        if (const GpuMesh* coarser = frame.res.meshes.get(*inst.asset, lod.level)) g = coarser;
    }
    glm::dmat4 rel = w;
    rel[3] = glm::dvec4(glm::dvec3(w[3]) - origin, 1.0);
    GpuObject o;
    o.model = glm::mat4(rel);
    o.normalMatrix = glm::mat4(glm::mat3(glm::inverseTranspose(glm::dmat3(w))));
    ShadowCaster c{g, centre - origin, double(g->bounds.radius()) * maxScale, {}, {}};
    if (frame.world.state) findCutouts(frame, *inst.asset, *g, c);
    casters.push_back(std::move(c));
    objects.push_back(o);
  }
}

void drawShadowCasters(RenderResources& resources, const std::vector<ShadowCaster>& casters,
                       const std::vector<uint32_t>& which) {
  auto draw = [](uint32_t first, uint32_t count, uint32_t instance) {
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                                        reinterpret_cast<const void*>(uintptr_t(first) * sizeof(uint32_t)), 1, instance);
  };
  resources.program({"mesh.vert", "shadow_depth.frag", "", {}}).use();
  bool anyCutout = false;
  for (uint32_t i : which) {
    const ShadowCaster& c = casters[i];
    glBindVertexArray(c.mesh->vao);
    if (c.cutouts.empty()) {
      draw(0, uint32_t(c.mesh->data->indices.size()), i);
      continue;
    }
    anyCutout = true;
    for (const auto& [first, count] : c.opaqueRanges) draw(first, count, i);
  }
  if (!anyCutout) return;
  GlProgram& cutout = resources.program({"mesh.vert", "shadow_depth.frag", "", {"ALPHA_CUTOUT"}});
  cutout.use();
  for (uint32_t i : which) {
    const ShadowCaster& c = casters[i];
    if (c.cutouts.empty()) continue;
    glBindVertexArray(c.mesh->vao);
    for (const CutoutPart& p : c.cutouts) {
      glBindTextureUnit(kMaterialTextureUnit, p.texture);
      cutout.set("uCutout", glm::vec4(p.opacity, p.threshold, p.texture ? 1.0f : 0.0f, p.translucent ? 1.0f : 0.0f));
      draw(p.firstIndex, p.indexCount, i);
    }
  }
  glBindTextureUnit(kMaterialTextureUnit, 0);
}

}  // namespace hs::render
