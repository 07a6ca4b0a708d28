#pragma once
// Depth of field as passes of a view (docs/rendering.md "Depth of field"):
// `gather` on the opaque HDR colour and depth, `layered` from the A-buffer
// (every surface's fragments, sorted per pixel, K layers blurred by their
// circle of confusion and composited front to back). The `reference` mode
// is not a pass: the renderer averages whole pinhole frames over the lens
// (render/dof_reference.h). Include only inside render/.
#include "render/dof_lens.h"
#include "render/passes/scene_passes.h"

namespace hs::render {

// Whether the frame needs depth of field for `view` at all: the setting is
// on, the view has a camera lens with valid values (a refused lens is
// reported through frame.res.dofProblems), and the largest circle of
// confusion in view reaches half a pixel (the nearest surface of the
// visible set, and the sky behind it). No: no pass and no buffer.
// `nearest`: the nearest drawn depth in `view` (nearestDrawnDepth, and the
// frame's sources' when they are known: framesNearestDepth).
bool depthOfFieldNeeded(const scene::SceneSettings& settings, RenderResources& res, const RenderView& view,
                        double nearest, DofLens* lens = nullptr);

// The nearest view depth (metres) of anything the frame draws in `view`:
// the visible meshes' bounding spheres, the near plane with a terrain.
double nearestDrawnDepth(const RenderWorld& world, const VisibleSet& visible, const RenderView& view);
// nearestDrawnDepth with the frame's draw sources too (foliage instances,
// particles: DrawSource::nearestDepth).
double framesNearestDepth(const FrameContext& frame, const RenderView& view);

// Will `view` of the frame take the layered depth of field? Then its
// capture has the translucent surfaces (and particles): the renderer adds
// no transparency pass for the view and hands it the colour before them.
bool layeredDepthOfField(FrameContext& frame, const RenderView& view);

// Adds the gather or layered passes after the HDR colour `hdr` and returns
// the blurred colour (`hdr` itself when depth of field is off or not needed).
TextureRef addDepthOfFieldPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                                 const SceneTargets& scene, TextureRef hdr);

// The largest CoC radius in pixels the post passes blur by (a larger one is
// drawn at this radius; the reference has no such limit).
inline constexpr double kDofMaxRadiusPixels = 32.0;

}  // namespace hs::render
