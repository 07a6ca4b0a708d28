#pragma once
// Screen-space ambient occlusion (settings.ao = ssao or gtao;
// docs/rendering.md): per view, after the MSAA resolve, an AO pass
// (shaders/ssao.frag or gtao.frag) reads the scene's depth
// (resolved to one sample) into an R8 visibility texture at half or full
// resolution, and an apply pass writes the scene colour with the ambient
// share (its alpha) occluded. Not added with AO off, so no AO texture
// exists then. Include only inside render/.
#include "render/passes/scene_passes.h"

namespace hs::render {

// Returns the occluded HDR colour (`hdr` itself when AO is off).
TextureRef addAmbientOcclusionPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                                     const SceneTargets& scene, TextureRef hdr);

}  // namespace hs::render
