#include "render/dof_reference.h"

#include <epoxy/gl.h>

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

TextureRef lensSumTexture(FrameGraph& graph, const ViewContext& v) {
  return graph.persistentTexture(v.named("dof_reference_sum"), TextureDesc{v.view.width, v.view.height, GL_RGBA32F});
}

void addLensSamplePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr, bool first,
                       float weight) {
  struct Data {
    TextureRef hdr, sum;
  };
  graph.addPass<Data>(
      v.named("dof_reference_sample"),
      [&](PassBuilder& b, Data& d) {
        d.hdr = b.read(hdr);
        d.sum = b.write(b.read(lensSumTexture(graph, v)));
        b.sideEffect();  // the sums outlive the frame (the last one's tone map reads them)
      },
      [&res = frame.res, first, weight, w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
        const GLuint sum = r.texture(d.sum);
        if (first || r.fresh(d.sum)) {
          const float zero[4] = {0, 0, 0, 0};
          glClearTexImage(sum, 0, GL_RGBA, GL_FLOAT, zero);
        }
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        FullscreenDraw draw;
        draw.fragment = "dof_accumulate.frag";
        draw.framebuffer = r.framebuffer({d.sum});
        draw.width = w;
        draw.height = h;
        draw.textures = {{24, r.texture(d.hdr)}};
        draw.uniforms = [weight](GlProgram& p) { p.set("uWeight", weight); };
        drawFullscreen(res, draw);
        glDisable(GL_BLEND);
      });
}

}  // namespace hs::render
