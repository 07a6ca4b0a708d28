#include "render/mesh_source.h"

#include <algorithm>

#include "render/frame_context.h"
#include "render/gpu_mesh_cache.h"
#include "render/material_binding.h"
#include "render/material_table.h"

namespace hs::render {
namespace {

void drawRange(uint32_t first, uint32_t count, uint32_t object) {
  glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                                      reinterpret_cast<const void*>(uintptr_t(first) * sizeof(uint32_t)), 1, object);
}

}  // namespace

bool MeshSource::wanted(size_t draw, size_t submesh, SurfaceSet surfaces) const {
  if (visible_.byOtherSource[draw]) return false;  // a cluster hierarchy draws it (cluster_source.h)
  if (surfaces == SurfaceSet::All) return true;
  return materials_.forDraw(draw, submesh).translucent == (surfaces == SurfaceSet::Translucent);
}

bool MeshSource::has(DrawVariant variant, SurfaceSet surfaces) const {
  switch (variant) {
    case DrawVariant::Pick: return visible_.inView > 0;
    case DrawVariant::Depth:
      for (const auto& c : casters_)
        if (!c.empty()) return true;
      return false;
    case DrawVariant::Surface:
      if (surfaces != SurfaceSet::Translucent)
        return std::find(visible_.byOtherSource.begin(), visible_.byOtherSource.begin() + long(visible_.inView), 0) !=
               visible_.byOtherSource.begin() + long(visible_.inView);
      for (size_t d = 0; d < visible_.inView; ++d)
        for (size_t s = 0; s < visible_.draws[d].mesh->data->submeshes.size(); ++s)
          if (wanted(d, s, surfaces)) return true;
      return false;
  }
  return false;
}

void MeshSource::cullShadowViews(FrameContext& frame, size_t first, size_t count) {
  casters_.resize(first + count);
  for (size_t v = first; v < first + count; ++v) {
    const Frustum& volume = frame.shadowViews[v];
    for (size_t i = 0; i < visible_.instances.size(); ++i) {
      const InstanceBounds& b = visible_.instances[i];
      // Casters are not limited to the camera views: a tree behind the
      // camera shadows the ground in front of it.
      if (b.radius >= 0.0 && volume.intersectsSphere(b.centre, b.radius)) {
        const uint32_t d = addCasterDraw(visible_, world_, cache_, i);
        if (!visible_.byOtherSource[d]) casters_[v].push_back(d);  // a hierarchy casts its own cut
      }
    }
  }
}

size_t MeshSource::triangles(SurfaceSet surfaces) const {
  size_t n = 0;
  for (size_t d = 0; d < visible_.inView; ++d) {
    const auto& subs = visible_.draws[d].mesh->data->submeshes;
    for (size_t s = 0; s < subs.size(); ++s)
      if (wanted(d, s, surfaces)) n += subs[s].indexCount / 3;
  }
  return n;
}

void MeshSource::draw(FrameContext& frame, const DrawCall& call, const PassResources&) {
  switch (call.variant) {
    case DrawVariant::Surface: drawSurfaceSet(frame, call); break;
    case DrawVariant::Depth:
      if (call.shadowView < casters_.size()) drawDepth(frame, casters_[call.shadowView]);
      break;
    case DrawVariant::Pick: {
      GlProgram& p = frame.res.program({"mesh.vert", "pick.frag", "", {}});
      p.use();
      p.set("uPickBase", call.pickBase);
      for (size_t d = 0; d < visible_.inView; ++d) {
        if (visible_.byOtherSource[d]) continue;
        const DrawItem& it = visible_.draws[d];
        glBindVertexArray(it.mesh->vao);
        for (const mesh::Submesh& sm : it.mesh->data->submeshes) drawRange(sm.firstIndex, sm.indexCount, it.object);
        frame.stats.drawCalls += it.mesh->data->submeshes.size();
      }
      break;
    }
  }
}

// The opaque pass's, the transparency passes' and the depth of field
// capture's draws, each submesh with its material (material_binding.h).
void MeshSource::drawSurfaceSet(FrameContext& frame, const DrawCall& call) const {
  if (visible_.inView == 0) return;
  const bool lit = call.surfaces == SurfaceSet::Opaque;  // the opaque pass counts what it draws
  MaterialBinding binding(frame, call.defines, call.fragment);
  for (size_t d = 0; d < visible_.inView; ++d) {
    const DrawItem& it = visible_.draws[d];
    const mesh::MeshData& m = *it.mesh->data;
    bool vaoBound = false;
    for (size_t s = 0; s < m.submeshes.size(); ++s) {
      if (!wanted(d, s, call.surfaces)) continue;
      if (!vaoBound) {
        glBindVertexArray(it.mesh->vao);
        vaoBound = true;
      }
      const mesh::Submesh& sm = m.submeshes[s];
      binding.apply(materials_.forDraw(d, s));
      drawRange(sm.firstIndex, sm.indexCount, it.object);
      if (lit) frame.stats.trianglesDrawn += sm.indexCount / 3;
      ++frame.stats.drawCalls;
    }
    if (lit && !visible_.byOtherSource[d]) ++frame.stats.instancesDrawn;
  }
  binding.finish();
}

// A shadow view's casters: whole meshes with the plain depth program (no
// cost for cut-out where nothing cuts out), then the cut-out and
// translucent submeshes with shadow_depth.frag's ALPHA_CUTOUT variant
// (built only when a caster has one).
void MeshSource::drawDepth(FrameContext& frame, const std::vector<uint32_t>& draws) const {
  auto castsCutout = [&](uint32_t d) {
    for (size_t s = 0; s < visible_.draws[d].mesh->data->submeshes.size(); ++s)
      if (materials_.forDraw(d, s).castsCutout) return true;
    return false;
  };
  frame.res.program({"mesh.vert", "shadow_depth.frag", "", {}}).use();
  std::vector<uint32_t> withCutout;
  for (uint32_t d : draws) {
    const DrawItem& it = visible_.draws[d];
    glBindVertexArray(it.mesh->vao);
    const bool cut = frame.world.state && castsCutout(d);
    if (!cut) {
      drawRange(0, uint32_t(it.mesh->data->indices.size()), it.object);
      continue;
    }
    withCutout.push_back(d);
    const auto& subs = it.mesh->data->submeshes;
    for (size_t s = 0; s < subs.size(); ++s)
      if (!materials_.forDraw(d, s).castsCutout) drawRange(subs[s].firstIndex, subs[s].indexCount, it.object);
  }
  if (withCutout.empty()) return;
  GlProgram& cutout = frame.res.program({"mesh.vert", "shadow_depth.frag", "", {"ALPHA_CUTOUT"}});
  cutout.use();
  for (uint32_t d : withCutout) {
    const DrawItem& it = visible_.draws[d];
    glBindVertexArray(it.mesh->vao);
    const auto& subs = it.mesh->data->submeshes;
    for (size_t s = 0; s < subs.size(); ++s) {
      const DrawMaterial& mat = materials_.forDraw(d, s);
      if (!mat.castsCutout) continue;
      bindCutout(cutout, mat);
      drawRange(subs[s].firstIndex, subs[s].indexCount, it.object);
    }
  }
  glBindTextureUnit(kMaterialTextureUnit, 0);
}

}  // namespace hs::render
