#include "render/draw_list.h"

#include "render/gpu_mesh_cache.h"
#include "render/passes/scene_passes.h"

namespace hs::render {

DrawList allSubmeshes(const VisibleSet& visible) {
  DrawList out;
  for (size_t d = 0; d < visible.draws.size(); ++d)
    for (size_t s = 0; s < visible.draws[d].mesh->data->submeshes.size(); ++s)
      out.push_back({uint32_t(d), uint32_t(s)});
  return out;
}

size_t triangleCount(const FrameContext& frame, const DrawList& list) {
  size_t n = 0;
  for (const SubmeshRef& ref : list) n += frame.visible.draws[ref.draw].mesh->data->submeshes[ref.submesh].indexCount / 3;
  return n;
}

void drawSubmeshes(FrameContext& frame, const DrawList& list, const std::vector<std::string>& defines,
                   const std::string& fragment) {
  if (list.empty()) return;
  const bool debugNormal = frame.options.debugShadingNormal;
  GlProgram* current = nullptr;
  GLuint bound[3] = {0, 0, 0};
  int culling = -1;
  uint32_t lastDraw = UINT32_MAX;
  for (const SubmeshRef& ref : list) {
    const DrawItem& it = frame.visible.draws[ref.draw];
    if (ref.draw != lastDraw) {
      glBindVertexArray(it.mesh->vao);
      lastDraw = ref.draw;
    }
    const mesh::Submesh& sm = it.mesh->data->submeshes[ref.submesh];
    const DrawMaterial& mat = frame.res.materials.forDraw(ref.draw, ref.submesh);
    GlProgram& p = fragment.empty()
                       ? frame.res.program(meshProgramDesc(mat.shading, mat.normalMap, mat.parallax, debugNormal, defines))
                       : frame.res.program({"mesh.vert", fragment, "", defines});
    if (&p != current) (current = &p)->use();
    p.set("uMaterial", unsigned(mat.index));
    for (unsigned u = 0; u < 3; ++u)
      if (mat.textures[u] && mat.textures[u] != bound[u])
        glBindTextureUnit(kMaterialTextureUnit + u, bound[u] = mat.textures[u]);
    if (int(!mat.twoSided) != culling) {
      culling = int(!mat.twoSided);
      culling ? glEnable(GL_CULL_FACE) : glDisable(GL_CULL_FACE);
    }
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                                        reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)), 1,
                                        it.object);
    ++frame.stats.drawCalls;
  }
  glDisable(GL_CULL_FACE);
  for (unsigned u = 0; u < 3; ++u) glBindTextureUnit(kMaterialTextureUnit + u, 0);
}

}  // namespace hs::render
