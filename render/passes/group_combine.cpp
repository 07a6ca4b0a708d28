#include "render/passes/group_combine.h"

#include <algorithm>

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

TextureRef addGroupCombinePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const std::vector<std::pair<TextureRef, float>>& images,
                               const CombinePattern& pattern) {
  FullscreenPass pass;
  pass.name = v.named("group_combine");
  pass.fragment = "group_combine.frag";
  const size_t n = std::min(images.size(), kMaxCombinedGroups);
  glm::vec4 weights(0.0f);
  for (size_t i = 0; i < n; ++i) {
    pass.inputs.emplace_back(unsigned(24 + i), images[i].first);
    weights[int(i)] = images[i].second;
  }
  pass.outputName = v.named("group_combined");
  pass.output = TextureDesc{v.view.width, v.view.height, GL_RGBA16F};
  // A pattern needs both shots; with fewer images the weights alone.
  const int mode = sequencer::isPatterned(pattern.transition) && n >= 2 ? int(pattern.transition) : 0;
  pass.uniforms = [weights, n, mode, pattern](GlProgram& p) {
    p.set("uWeights", weights);
    p.set("uImages", int(n));
    p.set("uPattern", mode);
    p.set("uProgress", pattern.progress);
    p.set("uFrame", unsigned(uint64_t(pattern.frame)));
  };
  return addFullscreenPass(graph, frame, v, std::move(pass));
}

}  // namespace hs::render
