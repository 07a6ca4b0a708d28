#pragma once
// Weighted Voronoi stippling (Secord 2002; docs/rendering.md "Stylised
// effects"), on the GPU: the image's darkness on a half-resolution grid,
// candidate dots at Halton points kept as the image is dark there (a fixed
// slot each: no compaction, no order), Lloyd
// relaxation moving each dot to the darkness-weighted centroid of its
// Voronoi cell (cells by jump flooding, sums by integer atomics: exact and
// order-free), then black dots drawn on white paper from the final cells.
// Include only inside render/.
#include "core/stipple_layout.h"
#include "render/frame_context.h"

namespace hs::render {

// The dots' picture from `ldr` (display-encoded): into the view's target
// with `toTarget`, else a new texture it returns. With the view's
// single-sample `depth` in a frame of two views (a stereo pair), the first
// view's dots are kept for the second: reprojected into it by depth (those
// it sees occluded or out of frame dropped) and held fixed, its own
// candidates filling only the places none lands near (disocclusions, the
// frame's edge), relaxed around them.
TextureRef addStipplePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                            bool toTarget, TextureRef depth = {});

}  // namespace hs::render
