#include "render/passes/bloom_passes.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "render/passes/fullscreen_pass.h"
#include "scene/light_units.h"

namespace hs::render {

BloomChain addBloomPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr) {
  const scene::PostSettings& post = frame.settings.post;
  constexpr int kMaxLevels = 6, kMinSide = 8;
  std::vector<TextureRef> down;
  std::vector<glm::ivec2> sizes;
  glm::ivec2 size{v.view.width, v.view.height};
  TextureRef source = hdr;
  glm::ivec2 sourceSize = size;
  for (int i = 0; i < kMaxLevels; ++i) {
    const glm::ivec2 next = sourceSize / 2;
    if (next.x < kMinSide || next.y < kMinSide) break;
    FullscreenPass p;
    p.name = v.named("bloom_down" + std::to_string(i));
    p.fragment = "bloom_down.frag";
    if (i == 0) p.defines = {"HS_BLOOM_PREFILTER"};
    p.inputs = {{0, source}};
    p.outputName = v.named("bloom_level" + std::to_string(i));
    p.output = TextureDesc{next.x, next.y, GL_RGBA16F};
    p.uniforms = [texel = glm::vec2(1.0f / float(sourceSize.x), 1.0f / float(sourceSize.y)),
                  exposure = float(scene::exposureMultiplier(frame.settings.exposureEv100)),
                  threshold = post.bloomThreshold](GlProgram& prog) {
      prog.set("uTexel", texel);
      prog.set("uExposure", exposure);
      prog.set("uThreshold", threshold);
    };
    source = addFullscreenPass(graph, frame, v, std::move(p));
    sourceSize = next;
    down.push_back(source);
    sizes.push_back(next);
  }
  BloomChain out;
  out.levels = int(down.size());
  if (down.empty()) return out;  // a view under 16 pixels: nothing to spread
  TextureRef coarse = down.back();
  float weight = 1.0f;
  for (int i = int(down.size()) - 2; i >= 0; --i) {
    FullscreenPass p;
    p.name = v.named("bloom_up" + std::to_string(i));
    p.fragment = "bloom_up.frag";
    p.inputs = {{0, coarse}, {1, down[size_t(i)]}};
    p.outputName = v.named("bloom_light" + std::to_string(i));
    p.output = TextureDesc{sizes[size_t(i)].x, sizes[size_t(i)].y, GL_RGBA16F};
    const glm::ivec2 c = sizes[size_t(i) + 1];
    p.uniforms = [texel = glm::vec2(1.0f / float(c.x), 1.0f / float(c.y)), radius = post.bloomRadius](GlProgram& prog) {
      prog.set("uTexel", texel);
      prog.set("uRadius", radius);
    };
    coarse = addFullscreenPass(graph, frame, v, std::move(p));
  }
  for (int i = 1; i < out.levels; ++i) weight += std::pow(post.bloomRadius, float(i));
  out.light = coarse;
  out.weightSum = weight;
  return out;
}

}  // namespace hs::render
