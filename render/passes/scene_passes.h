#pragma once
// The passes that fill a view's scene colour and depth: opaque meshes (which
// also create and clear the targets) and terrains. Include only inside
// render/.
#include "render/frame_context.h"

namespace hs::render {

struct SceneTargets {
  TextureRef color;  // linear HDR (RGBA16F), multisampled with MSAA
  TextureRef depth;  // reversed-Z float depth
  int samples = 1;
};

// The mesh program of a shading mode (shaders/mesh.frag's variants); built
// on first use, so a frame with no Gouraud material builds no Gouraud program.
// Normal and parallax mapping are variants too (HAS_NORMAL_MAP,
// HAS_PARALLAX, with the tangent attribute), and so is the debug output of
// the shading normal (DEBUG_SHADING_NORMAL, RenderOptions::debugShadingNormal)
// and the frame's fog (`extra`: fog_block.h fogDefines).
gl::ProgramDesc meshProgramDesc(scene::ShadingMode mode, bool normalMap = false, bool parallax = false,
                                bool debugNormal = false, const std::vector<std::string>& extra = {});

// Creates the view's scene targets, clears them, draws the visible meshes.
SceneTargets addOpaquePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view);
// Draws the visible terrains into `targets` (only added when there are
// any); returns the targets' new versions.
SceneTargets addTerrainPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets);

}  // namespace hs::render
