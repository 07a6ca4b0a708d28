#include "render/passes/group_combine.h"

#include <algorithm>
#include <string>

#include <epoxy/gl.h>

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

TextureRef addGroupCombinePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const std::vector<std::pair<TextureRef, float>>& images,
                               const CombinePattern& pattern, bool toTarget) {
  FullscreenPass pass;
  pass.name = v.named(toTarget ? "picture_combine" : "group_combine");
  pass.fragment = "group_combine.frag";
  const size_t n = std::min(images.size(), kMaxCombinedGroups);
  glm::vec4 weights(0.0f);
  for (size_t i = 0; i < n; ++i) {
    pass.inputs.emplace_back(unsigned(24 + i), images[i].first);
    weights[int(i)] = images[i].second;
  }
  if (toTarget) {
    pass.toTarget = true;
  } else {
    pass.outputName = v.named("group_combined");
    pass.output = TextureDesc{v.view.width, v.view.height, GL_RGBA16F};
  }
  // A pattern needs both shots; with fewer images the weights alone. Each
  // pattern is a program of its own (HS_PATTERN = the enum's value, which
  // the shader's #if blocks spell out).
  using T = sequencer::Transition;
  static_assert(int(T::CrossfadeBlur) == 3 && int(T::Swipe) == 4 && int(T::WaterDrop) == 5 &&
                    int(T::PixelDissolve) == 6 && int(T::Glitch) == 7 && int(T::ZoomBlur) == 8 &&
                    int(T::RadialWipe) == 9,
                "shaders/group_combine.frag numbers the patterns so");
  if (sequencer::isPatterned(pattern.transition) && n >= 2)
    pass.defines.push_back("HS_PATTERN " + std::to_string(int(pattern.transition)));
  pass.uniforms = [weights, n, pattern](GlProgram& p) {
    p.set("uWeights", weights);
    p.set("uImages", int(n));
    p.set("uProgress", pattern.progress);
    p.set("uFrame", unsigned(uint64_t(pattern.frame)));
  };
  return addFullscreenPass(graph, frame, v, std::move(pass));
}

TextureRef addTargetCopyPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, unsigned fbo,
                             const std::string& name) {
  (void)frame;
  struct Data {
    TextureRef to;
  };
  return graph
      .addPass<Data>(
          v.named(name + "_copy"),
          [&](PassBuilder& b, Data& d) {
            d.to = b.create(v.named(name), TextureDesc{v.view.width, v.view.height, GL_RGBA16});
          },
          [fbo, w = v.view.width, h = v.view.height](const Data& d, const PassResources& r) {
            glBlitNamedFramebuffer(fbo, r.framebuffer({d.to}), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT,
                                   GL_NEAREST);
          })
      .to;
}

}  // namespace hs::render
