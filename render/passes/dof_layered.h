#pragma once
// Layered depth of field from the A-buffer (docs/rendering.md "Depth of
// field"; Schedl & Wimmer 2012, the GPU Pro chapter): every surface of the
// view's meshes captured into per-pixel sorted ranges with no depth test
// (render/abuffer.h), each pixel's fragments sorted and split into K layers
// by circle of confusion (shaders/dof_layers.comp), each layer blurred by
// its CoC and the layers composited front to back with partial occlusion
// (shaders/dof_composite.frag). Include only inside render/.
#include "render/dof_lens.h"
#include "render/passes/scene_passes.h"

namespace hs::render {

// `hdr` and `depth`: the view's single-sample HDR colour and depth;
// `nearest`: the nearest drawn depth (passes/dof_passes.h). Returns the
// blurred colour ("dof_color").
TextureRef addLayeredDofPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view, TextureRef hdr,
                               TextureRef depth, const DofLens& lens, double nearest);

}  // namespace hs::render
