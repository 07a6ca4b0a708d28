#pragma once
// The passes from the scene's HDR colour to the caller's framebuffer:
// MSAA resolve (only with MSAA), the post chain (docs/rendering.md
// "Post-processing": bloom's levels only with bloom, then one pass for
// exposure, chromatic aberration, the tone map, the grade, the LUT (its
// OpenColorIO function and tables), the vignette, grain and sRGB encoding, each a shader define only when enabled), FXAA
// or SMAA (only when chosen; smaa_passes.h), the stylised effects (stylised_passes.h, only when one
// is on), the editor's before/after split (RenderOptions::postSplit), and a
// single-sample copy of the depth for the frames whose depth is read back
// (the stereo comfort check). Include only inside render/.
#include "render/passes/scene_passes.h"

namespace hs::render {

// The single-sample HDR colour: the scene colour itself without MSAA.
TextureRef addResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets);
// Single-sample depth (a copy, one sample per pixel, with MSAA).
TextureRef addDepthResolvePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                               const SceneTargets& targets);
// The post chain on `hdr` into the view's target framebuffer, or, with
// FXAA or SMAA, into an LDR texture that their passes draw into the target.
// `depth` (single-sample), where given, lets stippling and error diffusion
// attach the second eye's pattern to the first eye's (stereo pairs).
void addToneMapPasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view, TextureRef hdr,
                      TextureRef depth = {});
// The tone map pass's defines for `settings` (one per enabled effect).
std::vector<std::string> postDefines(const scene::SceneSettings& settings);
// White balance as per-channel gains (settings.post.grade.temperature, .tint).
glm::vec3 whiteBalanceGains(float temperature, float tint);

}  // namespace hs::render
