#include "render/passes/output_passes.h"

#include "render/passes/fullscreen_pass.h"
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
  FullscreenPass tm;
  tm.name = v.named("tonemap");
  tm.fragment = "tonemap.frag";
  tm.inputs = {{0, hdr}};
  if (fxaa) {
    tm.outputName = v.named("ldr_color");
    tm.output = TextureDesc{v.view.width, v.view.height, GL_RGBA8};
  } else {
    tm.toTarget = true;  // draws into the caller's framebuffer
  }
  tm.uniforms = [&frame, fxaa](GlProgram& p) {
    p.set("uExposure", float(scene::exposureMultiplier(frame.settings.exposureEv100)));
    p.set("uFilmic", frame.settings.tonemap == scene::Tonemap::Aces);
    p.set("uLumaInAlpha", fxaa);
  };
  const TextureRef ldr = addFullscreenPass(graph, frame, v, std::move(tm));
  if (!fxaa) return;
  FullscreenPass aa;
  aa.name = v.named("fxaa");
  aa.fragment = "fxaa.frag";
  aa.inputs = {{0, ldr}};
  aa.toTarget = true;
  aa.uniforms = [w = v.view.width, h = v.view.height](GlProgram& p) {
    p.set("uTexel", glm::vec2(1.0f / float(w), 1.0f / float(h)));
  };
  addFullscreenPass(graph, frame, v, std::move(aa));
}

}  // namespace hs::render
