#include "render/passes/fullscreen_pass.h"

namespace hs::render {

void drawFullscreen(RenderResources& res, const FullscreenDraw& draw) {
  glBindFramebuffer(GL_FRAMEBUFFER, draw.framebuffer);
  glViewport(0, 0, draw.width, draw.height);
  if (draw.depthFunc) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(draw.depthFunc);
    glDepthMask(draw.depthWrite ? GL_TRUE : GL_FALSE);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  if (draw.view >= 0) res.bindView(size_t(draw.view));
  GlProgram& p = res.program({"fullscreen.vert", draw.fragment, "", draw.defines, draw.generated});
  p.use();
  if (draw.uniforms) draw.uniforms(p);
  for (const auto& [unit, texture] : draw.textures) glBindTextureUnit(unit, texture);
  glBindVertexArray(res.emptyVao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  for (const auto& [unit, texture] : draw.textures) glBindTextureUnit(unit, 0);
  glEnable(GL_DEPTH_TEST);
  if (draw.depthFunc) {
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
  }
}

TextureRef addFullscreenPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, FullscreenPass pass) {
  struct Data {
    std::vector<std::pair<unsigned, TextureRef>> inputs;
    TextureRef out;
  };
  const std::string name = pass.name;
  return graph
      .addPass<Data>(
          name,
          [&](PassBuilder& b, Data& d) {
            for (const auto& [unit, t] : pass.inputs) d.inputs.emplace_back(unit, b.read(t));
            if (pass.toTarget) b.sideEffect();
            else d.out = b.create(pass.outputName, pass.output);
          },
          [&frame, p = pass, target = v.target, index = int(v.index), w = v.view.width,
           h = v.view.height](const Data& d, const PassResources& r) {
            FullscreenDraw draw;
            draw.fragment = p.fragment;
            draw.defines = p.defines;
            draw.generated = p.generated;
            draw.framebuffer = p.toTarget ? target : r.framebuffer({d.out});
            draw.width = p.toTarget ? w : p.output.width;
            draw.height = p.toTarget ? h : p.output.height;
            for (const auto& [unit, t] : d.inputs) draw.textures.emplace_back(unit, r.texture(t));
            draw.uniforms = p.uniforms;
            draw.view = p.bindView ? index : -1;
            drawFullscreen(frame.res, draw);
          })
      .out;
}

}  // namespace hs::render
