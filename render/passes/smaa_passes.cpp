#include "render/passes/smaa_passes.h"

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

TextureRef addSmaaPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr, bool toTarget) {
  const int w = v.view.width, h = v.view.height;
  FullscreenPass edges;
  edges.name = v.named("smaa_edges");
  edges.fragment = "smaa_edges.frag";
  edges.inputs = {{0, ldr}};
  edges.outputName = v.named("smaa_edges");
  edges.output = TextureDesc{w, h, GL_RG8};
  edges.uniforms = [](GlProgram& p) { p.set("uThreshold", kSmaaThreshold); };
  const TextureRef edgeTex = addFullscreenPass(graph, frame, v, std::move(edges));

  FullscreenPass weights;
  weights.name = v.named("smaa_weights");
  weights.fragment = "smaa_weights.frag";
  weights.inputs = {{0, edgeTex}};
  weights.outputName = v.named("smaa_weights");
  weights.output = TextureDesc{w, h, GL_RGBA8};
  weights.uniforms = [](GlProgram& p) { p.set("uMaxSearch", kSmaaMaxSearch); };
  const TextureRef weightTex = addFullscreenPass(graph, frame, v, std::move(weights));

  FullscreenPass blend;
  blend.name = v.named("smaa_blend");
  blend.fragment = "smaa_blend.frag";
  blend.inputs = {{0, ldr}, {1, weightTex}};
  if (toTarget) {
    blend.toTarget = true;
  } else {
    blend.outputName = v.named("ldr_antialiased");
    blend.output = TextureDesc{w, h, GL_RGBA8};
  }
  return addFullscreenPass(graph, frame, v, std::move(blend));
}

}  // namespace hs::render
