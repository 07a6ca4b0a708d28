#include "render/dof_reference.h"

#include <epoxy/gl.h>

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

GLuint acquireLensAccumulation(RenderResources& res, int width, int height) {
  const GLuint tex = res.pool.acquireTexture(TextureDesc{width, height, GL_RGBA32F}, "dof_reference_accum");
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, zero);
  return tex;
}

void accumulateLensSample(RenderResources& res, GLuint frame, GLuint accum, int width, int height, float weight) {
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  FullscreenDraw draw;
  draw.fragment = "dof_accumulate.frag";
  draw.framebuffer = res.pool.framebuffer({accum}, 0);
  draw.width = width;
  draw.height = height;
  draw.textures = {{24, frame}};
  draw.uniforms = [weight](GlProgram& p) { p.set("uWeight", weight); };
  drawFullscreen(res, draw);
  glDisable(GL_BLEND);
}

}  // namespace hs::render
