#pragma once
// Weighted Voronoi stippling (Secord 2002; docs/rendering.md "Stylised
// effects"), on the GPU: the image's darkness on a half-resolution grid,
// candidate dots at Halton points kept as the image is dark there (a fixed
// slot each: no compaction, the same pattern in both eyes), Lloyd
// relaxation moving each dot to the darkness-weighted centroid of its
// Voronoi cell (cells by jump flooding, sums by integer atomics: exact and
// order-free), then black dots drawn on white paper from the final cells.
// Include only inside render/.
#include "core/stipple_layout.h"
#include "render/frame_context.h"

namespace hs::render {

// The dots' picture from `ldr` (display-encoded): into the view's target
// with `toTarget`, else a new texture it returns.
TextureRef addStipplePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                            bool toTarget);

}  // namespace hs::render
