#include "render/passes/dof_layered.h"

#include <algorithm>

#include "render/abuffer.h"
#include "render/draw_source.h"
#include "render/passes/dof_passes.h"
#include "render/passes/fullscreen_pass.h"

namespace hs::render {
namespace {

// The uniforms of shaders/dof_common.glsl and the layers' CoC range.
void setLayerUniforms(GlProgram& p, const RenderView& view, const DofLens& lens, double nearest, int layers) {
  const glm::dmat4 proj = view.projection();
  const double maxRadius = std::min(0.5 * maxCocPixels(lens, nearest), kDofMaxRadiusPixels);
  p.set("uCocScale", float(lens.cocScale));
  p.set("uInvFocus", float(1.0 / lens.focusDistance));
  p.set("uDepthToInvZ", glm::vec2(float(proj[2][2]), float(proj[3][2])));
  p.set("uMaxRadius", float(maxRadius));
  p.set("uLayers", layers);
  // Signed radii from the nearest drawn surface to infinity, as the shader clamps them.
  const double nearCoc = std::clamp(0.5 * lens.cocPixels(nearest), -maxRadius, maxRadius);
  const double farCoc = std::clamp(0.5 * lens.cocPixels(INFINITY), -maxRadius, maxRadius);
  p.set("uCocRange", glm::vec2(float(std::min(nearCoc, farCoc)), float(std::max(nearCoc, farCoc))));
}

}  // namespace

TextureRef addLayeredDofPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr,
                               TextureRef depth, const DofLens& lens, double nearest) {
  const int layers = std::clamp(frame.settings.dofLayers, 2, 16);
  const int w = v.view.width, h = v.view.height;
  ABufferRequest request;
  request.name = "dof";
  request.draws = SurfaceSet::All;
  request.depth = depth;
  request.depthTest = ABufferDepthTest::None;  // every surface, the hidden ones too
  const ABuffer abuffer = addABufferCapture(graph, frame, v, request);  // the caller made sure a mesh is in view

  struct Layers {
    TextureRef hdr, depth, color, coc;
  };
  const Layers& split = graph.addPass<Layers>(
      v.named("dof_layers"),
      [&](PassBuilder& b, Layers& d) {
        d.hdr = b.read(hdr);
        d.depth = b.read(depth);
        readABuffer(b, abuffer);
        TextureDesc array{w, h, GL_RGBA16F};
        array.layers = layers;
        array.array = true;
        d.color = b.create(v.named("dof_layer_color"), array, Usage::Storage);
        array.format = GL_R16F;
        d.coc = b.create(v.named("dof_layer_coc"), array, Usage::Storage);
      },
      [&frame, view = v.view, lens, nearest, layers, abuffer](const Layers& d, const PassResources& r) {
        GlProgram& p = frame.res.program({"", "", "dof_layers.comp", {}});
        setLayerUniforms(p, view, lens, nearest, layers);
        p.use();
        bindABuffer(abuffer, r);
        glBindTextureUnit(24, r.texture(d.hdr));
        glBindTextureUnit(25, r.texture(d.depth));
        glBindImageTexture(4, r.texture(d.color), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(5, r.texture(d.coc), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16F);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDispatchCompute(GLuint((view.width + 7) / 8), GLuint((view.height + 7) / 8), 1);
        // The composite's texture fetch barrier: the graph's (Usage::Storage writes).
        glBindTextureUnit(24, 0);
        glBindTextureUnit(25, 0);
      });

  FullscreenPass composite;
  composite.name = v.named("dof_composite");
  composite.fragment = "dof_composite.frag";
  composite.inputs = {{26, split.color}, {27, split.coc}};
  composite.outputName = v.named("dof_color");
  composite.output = TextureDesc{w, h, GL_RGBA16F};
  composite.uniforms = [view = v.view, lens, nearest, layers](GlProgram& p) {
    setLayerUniforms(p, view, lens, nearest, layers);
  };
  return addFullscreenPass(graph, frame, v, std::move(composite));
}

}  // namespace hs::render
