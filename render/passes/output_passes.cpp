#include "render/passes/output_passes.h"

#include "scene/light_units.h"

namespace hs::render {

TextureRef addResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  (void)frame;
  if (targets.samples <= 1) return targets.color;
  struct Data {
    TextureRef from, to;
  };
  return graph
      .addPass<Data>(
          v.named("resolve"),
          [&](PassBuilder& b, Data& d) {
            d.from = b.read(targets.color);
            d.to = b.create(v.named("hdr_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F});
          },
          [w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            glBlitNamedFramebuffer(r.framebuffer({d.from}), r.framebuffer({d.to}), 0, 0, w, h, 0, 0, w, h,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
          })
      .to;
}

TextureRef addDepthResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const SceneTargets& targets) {
  (void)frame;
  if (targets.samples <= 1) return targets.depth;
  struct Data {
    TextureRef from, to;
  };
  return graph
      .addPass<Data>(
          v.named("depth_resolve"),
          [&](PassBuilder& b, Data& d) {
            d.from = b.read(targets.depth);
            d.to = b.create(v.named("depth"), TextureDesc{v.view.width, v.view.height, GL_DEPTH_COMPONENT32F});
          },
          [w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            // Depth is not averaged: one sample per pixel, which is what a
            // parallax extreme should come from (an averaged edge depth
            // belongs to no surface).
            glBlitNamedFramebuffer(r.framebuffer({}, d.from), r.framebuffer({}, d.to), 0, 0, w, h, 0, 0, w, h,
                                   GL_DEPTH_BUFFER_BIT, GL_NEAREST);
          })
      .to;
}

void addToneMapPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr) {
  const bool fxaa = frame.settings.antialiasing == scene::Antialiasing::Fxaa;
  struct Data {
    TextureRef hdr, ldr;
  };
  const Data& tm = graph.addPass<Data>(
      v.named("tonemap"),
      [&](PassBuilder& b, Data& d) {
        d.hdr = b.read(hdr);
        if (fxaa) d.ldr = b.create(v.named("ldr_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA8});
        else b.sideEffect();  // draws into the caller's framebuffer
      },
      [&frame, target = v.target, w = v.view.width, h = v.view.height, fxaa](const Data& d, const PassResources& r) {
        GlProgram& p = frame.res.program({"fullscreen.vert", "tonemap.frag", "", {}});
        p.use();
        p.set("uExposure", float(scene::exposureMultiplier(frame.settings.exposureEv100)));
        p.set("uFilmic", frame.settings.tonemap == scene::Tonemap::Aces);
        p.set("uLumaInAlpha", fxaa);
        glBindFramebuffer(GL_FRAMEBUFFER, fxaa ? r.framebuffer({d.ldr}) : target);
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glBindTextureUnit(0, r.texture(d.hdr));
        glBindVertexArray(frame.res.emptyVao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
      });
  if (!fxaa) return;
  graph.addPass<Data>(
      v.named("fxaa"),
      [&](PassBuilder& b, Data& d) {
        d.ldr = b.read(tm.ldr);
        b.sideEffect();
      },
      [&frame, target = v.target, w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
        GlProgram& p = frame.res.program({"fullscreen.vert", "fxaa.frag", "", {}});
        p.use();
        p.set("uTexel", glm::vec2(1.0f / float(w), 1.0f / float(h)));
        glBindFramebuffer(GL_FRAMEBUFFER, target);
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glBindTextureUnit(0, r.texture(d.ldr));
        glBindVertexArray(frame.res.emptyVao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
      });
}

}  // namespace hs::render
