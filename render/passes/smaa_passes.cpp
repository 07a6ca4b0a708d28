#include "render/passes/smaa_passes.h"

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

namespace {

// The edges and a depth mask of the edge pixels: the edge shader discards
// the others, so only edge pixels get the full-screen triangle's depth (the
// far value, 0) over a clear of 1. The weights pass tests GL_EQUAL against
// it and shades the edge pixels alone (as SMAA does with a stencil): on
// llvmpipe the test comes before the shader and a block without an edge
// costs nothing.
struct Edges {
  TextureRef edges, mask;
};

Edges addEdges(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr) {
  struct Data {
    TextureRef in;
    Edges out;
  };
  const int w = v.view.width, h = v.view.height;
  return graph
      .addPass<Data>(
          v.named("smaa_edges"),
          [&](PassBuilder& b, Data& d) {
            d.in = b.read(ldr);
            d.out.edges = b.create(v.named("smaa_edges"), TextureDesc{w, h, GL_RG8});
            d.out.mask = b.create(v.named("smaa_edge_mask"), TextureDesc{w, h, GL_DEPTH_COMPONENT16});
          },
          [&frame, w, h](const Data& d, const PassResources& r) {
            FullscreenDraw draw;
            draw.fragment = "smaa_edges.frag";
            draw.framebuffer = r.framebuffer({d.out.edges}, d.out.mask);
            draw.width = w;
            draw.height = h;
            draw.textures = {{0, r.texture(d.in)}};
            draw.uniforms = [](GlProgram& p) { p.set("uThreshold", kSmaaThreshold); };
            draw.depthFunc = GL_ALWAYS;
            draw.depthWrite = true;
            const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f}, cleared = 1.0f;
            glDepthMask(GL_TRUE);  // a clear obeys the depth mask
            glClearNamedFramebufferfv(draw.framebuffer, GL_COLOR, 0, none);
            glClearNamedFramebufferfv(draw.framebuffer, GL_DEPTH, 0, &cleared);
            drawFullscreen(frame.res, draw);
          })
      .out;
}

TextureRef addWeights(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const Edges& edges) {
  struct Data {
    TextureRef edges, mask, weights;
  };
  const int w = v.view.width, h = v.view.height;
  return graph
      .addPass<Data>(
          v.named("smaa_weights"),
          [&](PassBuilder& b, Data& d) {
            d.edges = b.read(edges.edges);
            d.mask = b.read(edges.mask, Usage::RenderTarget);
            d.weights = b.create(v.named("smaa_weights"), TextureDesc{w, h, GL_RGBA8});
          },
          [&frame, w, h](const Data& d, const PassResources& r) {
            FullscreenDraw draw;
            draw.fragment = "smaa_weights.frag";
            draw.framebuffer = r.framebuffer({d.weights}, d.mask);
            draw.width = w;
            draw.height = h;
            draw.textures = {{0, r.texture(d.edges)}};
            draw.uniforms = [](GlProgram& p) { p.set("uMaxSearch", kSmaaMaxSearch); };
            draw.depthFunc = GL_EQUAL;  // edge pixels only; the rest keep the clear's 0
            const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            glClearNamedFramebufferfv(draw.framebuffer, GL_COLOR, 0, none);
            drawFullscreen(frame.res, draw);
          })
      .weights;
}

}  // namespace

TextureRef addSmaaPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr, bool toTarget) {
  const int w = v.view.width, h = v.view.height;
  const TextureRef weightTex = addWeights(graph, frame, v, addEdges(graph, frame, v, ldr));

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
