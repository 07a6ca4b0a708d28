#include "render/dof_reference.h"

#include <epoxy/gl.h>

namespace hs::render {

GLuint acquireLensAccumulation(RenderResources& res, int width, int height) {
  const GLuint tex = res.pool.acquireTexture(TextureDesc{width, height, GL_RGBA32F}, "dof_reference_accum");
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, zero);
  return tex;
}

void accumulateLensSample(RenderResources& res, GLuint frame, GLuint accum, int width, int height, float weight) {
  glBindFramebuffer(GL_FRAMEBUFFER, res.pool.framebuffer({accum}, 0));
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  GlProgram& p = res.program({"fullscreen.vert", "dof_accumulate.frag", "", {}});
  p.set("uWeight", weight);
  p.use();
  glBindTextureUnit(24, frame);
  glBindVertexArray(res.emptyVao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindTextureUnit(24, 0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace hs::render
