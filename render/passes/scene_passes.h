#pragma once
// The passes that fill a view's scene colour and depth with the frame's
// draw sources (draw_source.h): the opaque pass (which also creates and
// clears the targets) draws every source without a lit pass of its own,
// then each source that has one (terrain) draws in its own. Include only
// inside render/.
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

// Creates the view's scene targets, clears them, draws the opaque surfaces
// of the sources without a pass of their own (meshes).
SceneTargets addOpaquePass(FrameGraph& graph, FrameContext& frame, const ViewContext& view);
// One pass per source with a lit pass of its own that has something to
// draw (terrain: only for scenes with a visible terrain), into `targets`;
// returns the targets' new versions.
SceneTargets addSourcePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& view, SceneTargets targets);

}  // namespace hs::render
