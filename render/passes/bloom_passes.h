#pragma once
// Bloom (docs/rendering.md "Post-processing"): the exposed scene light
// above a threshold spread by a chain of half-size levels, the dual filter
// (Bjorge 2015: a five-tap downsample, an eight-tap tent upsample), each
// coarser level added with the radius as its weight. Added only when
// settings.post.bloom is on; the tone map pass adds the result. Include
// only inside render/.
#include "render/passes/scene_passes.h"

namespace hs::render {

struct BloomChain {
  TextureRef light;        // half the view's size: sum over levels i of radius^i x level i
  float weightSum = 1.0f;  // sum of radius^i: the light over it keeps the prefiltered light's mean
  int levels = 0;
};

// The passes bloom_down0..N-1 (the first one exposes and thresholds
// `hdr`) and bloom_up N-2..0; N halvings until a side would go under 8
// pixels, at most 6.
BloomChain addBloomPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr);

}  // namespace hs::render
