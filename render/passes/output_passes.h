#pragma once
// The passes from the scene's HDR colour to the caller's framebuffer:
// MSAA resolve (only with MSAA), tone mapping with sRGB encoding, FXAA
// (only with FXAA), and a single-sample copy of the depth for the frames
// whose depth is read back (the stereo comfort check). Include only inside
// render/.
#include "render/passes/scene_passes.h"

namespace hs::render {

// The single-sample HDR colour: the scene colour itself without MSAA.
TextureRef addResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets);
// Single-sample depth (a copy, one sample per pixel, with MSAA).
TextureRef addDepthResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                               const SceneTargets& targets);
// Tone maps `hdr` into the view's target framebuffer, or, with FXAA, into
// an LDR texture that the FXAA pass then draws into the target.
void addToneMapPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view, TextureRef hdr);

}  // namespace hs::render
