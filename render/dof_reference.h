#pragma once
// Depth of field's reference (settings.depth_of_field = reference,
// docs/rendering.md "Depth of field"): the average of N whole pinhole frames
// rendered from points of the lens's aperture (dof_lens.h lensDiscSamples,
// lensSampleView: a fixed seed, the focus plane held still), summed in
// float. Slow by design (N real renders); tests and bench_dof measure the
// post passes against it. Renderer::renderViews drives the loop; the sums
// are persistent textures of the frame graph, one per view. Include only
// inside render/.
#include "render/frame_context.h"

namespace hs::render {

// View v's sum ("dof_reference_sum" and the view's suffix: RGBA32F, the
// view's size), a persistent texture that lives while frames ask for it.
TextureRef lensSumTexture(FrameGraph& graph, const ViewContext& v);

// The "dof_reference_sample" pass of a lens sample's frame: sum += weight
// * hdr (additive blending), the sum cleared first when `first`.
void addLensSamplePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef hdr, bool first,
                       float weight);

}  // namespace hs::render
