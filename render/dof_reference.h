#pragma once
// Depth of field's reference (settings.depth_of_field = reference,
// docs/rendering.md "Depth of field"): the average of N whole pinhole frames
// rendered from points of the lens's aperture (dof_lens.h lensDiscSamples,
// lensSampleView: a fixed seed, the focus plane held still), summed in
// float. Slow by design (N real renders); tests and bench_dof measure the
// post passes against it. Renderer::renderViews drives the loop; this is
// its GL part. Include only inside render/.
#include "render/render_resources.h"

namespace hs::render {

// An RGBA32F accumulation target of w x h, cleared to 0 (from the pool,
// named "dof_reference_accum"; release it with pool.releaseTexture).
GLuint acquireLensAccumulation(RenderResources& res, int width, int height);

// accum += weight * frame (an HDR texture of the same size).
void accumulateLensSample(RenderResources& res, GLuint frame, GLuint accum, int width, int height, float weight);

}  // namespace hs::render
