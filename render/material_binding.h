#pragma once
// What every draw source does per part it draws with a material (mesh
// source, instanced source): choose the program of the material's variant
// (built on first use: none for shading modes nobody uses), set its
// material index and its submesh's UV range (shaders/mesh_uv.glsl), bind
// the textures that changed, cull the back faces of one-sided materials;
// and for shadow casters, the cut-out uniforms of
// shaders/shadow_depth.frag. One object per draw loop; finish() leaves the
// state as it found it. Include only inside render/.
#include <string>
#include <vector>

#include "render/frame_context.h"
#include "render/material_table.h"

namespace hs::render {

class MaterialBinding {
 public:
  // `defines`: the pass's (fog, a transparency mode, INSTANCED); `fragment`:
  // a pass's own fragment shader instead of the material's (no material then).
  MaterialBinding(FrameContext& frame, std::vector<std::string> defines, std::string fragment = {});
  // The program for `mat`, in use, with the material's index and textures bound.
  GlProgram& apply(const DrawMaterial& mat);
  void finish();

 private:
  FrameContext& frame_;
  std::vector<std::string> defines_;
  std::string fragment_;
  GlProgram* programs_[3][2][2] = {};
  GlProgram* current_ = nullptr;
  GLuint bound_[3] = {0, 0, 0};
  int culling_ = -1;
};

// shadow_depth.frag's ALPHA_CUTOUT inputs for a caster's material: its base
// colour texture, uCutout (opacity, threshold, textured, hashed) and the
// submesh's UV range (uUvBounds, shaders/mesh_uv.glsl).
void bindCutout(GlProgram& program, const DrawMaterial& mat);

}  // namespace hs::render
