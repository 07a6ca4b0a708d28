#pragma once
// The stylised effects after the post chain (docs/rendering.md "Stylised
// effects"), on the display-encoded image: the anisotropic Kuwahara filter
// (three passes: structure tensor, its smoothing and orientation, the
// filter), one pass for the per-pixel effects (comic, outlines, CRT,
// ordered dithering; shaders/stylise.frag), weighted Voronoi stippling
// (stipple_passes.h), and Floyd-Steinberg error
// diffusion (a compute pass, then a copy into the target), each only when
// enabled, the last drawing into the view's framebuffer. Include only
// inside render/.
#include <string>
#include <vector>

#include "render/frame_context.h"

namespace hs::render {

// Whether any stylised effect of `post` is on (then the chain before ends
// in a texture these passes read).
bool stylisedEffectsOn(const scene::PostSettings& post);
// The per-pixel pass's defines (empty: no such pass).
std::vector<std::string> stylisePassDefines(const scene::PostSettings& post);
// The blue-noise threshold map's side (core/blue_noise.h), in pixels.
constexpr int kBlueNoiseSide = 64;

// `ldr`: the display-encoded image of the view.
void addStylisedPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                       TextureRef depth = {});

}  // namespace hs::render
