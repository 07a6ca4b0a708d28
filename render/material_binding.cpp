#include "render/material_binding.h"

#include "render/passes/scene_passes.h"

namespace hs::render {

MaterialBinding::MaterialBinding(FrameContext& frame, std::vector<std::string> defines, std::string fragment)
    : frame_(frame), defines_(std::move(defines)), fragment_(std::move(fragment)) {}

GlProgram& MaterialBinding::apply(const DrawMaterial& mat) {
  GlProgram* p = nullptr;
  if (!fragment_.empty()) {
    p = &frame_.res.program({"mesh.vert", fragment_, "", defines_});
  } else {
    GlProgram*& cached = programs_[int(mat.shading)][mat.normalMap][mat.parallax];
    if (!cached)
      cached = &frame_.res.program(meshProgramDesc(mat.shading, mat.normalMap, mat.parallax,
                                                   frame_.options.debugShadingNormal, defines_));
    p = cached;
  }
  if (p != current_) (current_ = p)->use();
  p->set("uMaterial", unsigned(mat.index));
  p->set("uUvBounds", mat.uvBounds);  // shaders/mesh_uv.glsl
  for (unsigned u = 0; u < 3; ++u)
    if (mat.textures[u] && mat.textures[u] != bound_[u]) glBindTextureUnit(kMaterialTextureUnit + u, bound_[u] = mat.textures[u]);
  // One-sided materials cull their back faces; scans are seen from both sides.
  if (int(!mat.twoSided) != culling_) {
    culling_ = int(!mat.twoSided);
    culling_ ? glEnable(GL_CULL_FACE) : glDisable(GL_CULL_FACE);
  }
  return *p;
}

void MaterialBinding::finish() {
  glDisable(GL_CULL_FACE);
  for (unsigned u = 0; u < 3; ++u) glBindTextureUnit(kMaterialTextureUnit + u, 0);
}

void bindCutout(GlProgram& program, const DrawMaterial& mat) {
  glBindTextureUnit(kMaterialTextureUnit, mat.textures[0]);
  program.set("uCutout", glm::vec4(mat.opacity, mat.alphaThreshold, mat.textures[0] ? 1.0f : 0.0f,
                                   mat.translucent ? 1.0f : 0.0f));
  program.set("uUvBounds", mat.uvBounds);
}

}  // namespace hs::render
