#pragma once
// SMAA (settings.antialiasing = SMAA; docs/rendering.md "Anti-aliasing"):
// morphological anti-aliasing of the tone-mapped picture in three passes,
// after Jimenez et al., "SMAA: Enhanced Subpixel Morphological
// Antialiasing" (2012), its 1x mode with orthogonal and diagonal patterns
// and corner detection: luma edges with local contrast adaptation
// ("smaa_edges", RG8, and a depth mask of the edge pixels,
// "smaa_edge_mask"), blending weights from each edge line's shape with the
// area of the rebuilt outline integrated exactly in the shader instead of
// read from SMAA's precomputed area textures ("smaa_weights", RGBA8, shaded
// at the edge pixels only through the mask), then each pixel mixed with its
// neighbours ("smaa_blend"). Each eye of a stereo pair runs it on its own
// picture with the same parameters.
// Include only inside render/.
#include "render/frame_context.h"

namespace hs::render {

// SMAA's "medium" preset: a luma step of 0.1, lines followed 16 pixels each way.
constexpr float kSmaaThreshold = 0.1f;
constexpr int kSmaaMaxSearch = 16;

// The passes on `ldr` (display values); the result into the view's
// framebuffer with `toTarget` (an invalid ref then), else a new RGBA8 texture.
TextureRef addSmaaPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr, bool toTarget);

}  // namespace hs::render
