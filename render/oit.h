#pragma once
// Transparency (issue 13; docs/rendering.md "Transparency"): translucent
// submeshes (opacity under 1, no alpha cut-out: DrawMaterial::translucent)
// are left out of the opaque pass and drawn here after the opaque
// geometry, sky and ambient occlusion, lit by the same mesh shader, then
// composited over the opaque colour by the mode of settings.transparency:
//   abuffer        every fragment in per-pixel ranges (render/abuffer.h), sorted per pixel
//   abuffer_fixed  the thesis's fixed array of 16 layers per pixel (the same capture), the nearest kept
//   kbuffer        the K nearest (settings.kbuffer_k) without interlock, the rest tail-blended
//   weighted       weighted blended OIT (McGuire & Bavoil 2013)
//   reference      depth peeling until no fragment is left
// A frame with no translucent submesh in view adds no pass and allocates
// nothing. Include only inside render/.
#include <memory>
#include <vector>

#include "render/abuffer.h"
#include "render/draw_source.h"
#include "render/frame_context.h"

namespace hs::render {

// What one view's transparency passes found (read after execute).
struct OitViewInfo {
  std::shared_ptr<ABufferInfo> counts;  // fragments, max, covered (when counted)
  size_t bytes = 0;                     // the OIT resources' GPU memory
  uint64_t overflow = 0;                // fragments that went to the tail
  double tailShare = 0.0;               // sum over pixels of the tail's share of the pixel
  uint64_t tailPixels = 0;
  int layers = 0;                       // abuffer_fixed: layers (16 unless the cap says fewer); kbuffer: K; abuffer: the per-pixel cap (0: none)
  int peels = 0;                        // reference: layers peeled
  bool ran = false;
};

// Adds the view's transparency passes over `hdr` (the opaque colour,
// single-sample) with `depth` (the opaque depth, single-sample) and returns
// the composited colour; `hdr` itself when no source has such surfaces. `counted`
// adds a counting pass to modes that have none of their own (weighted,
// reference) so their fragments per pixel are known.
TextureRef addTransparencyPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                                 SurfaceSet draws, TextureRef depth, TextureRef hdr, bool counted,
                                 std::shared_ptr<OitViewInfo>& info);

// Draws the view's depth complexity (fragments per pixel of `draws`) as a
// heat map over `hdr` (RenderOptions::depthComplexity).
TextureRef addDepthComplexityPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                                  SurfaceSet draws, TextureRef depth, TextureRef hdr);

}  // namespace hs::render
