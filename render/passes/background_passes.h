#pragma once
// The passes drawn over the scene before it is resolved: the sky where
// nothing was drawn, the ground grid and the editor's overlays (blended).
// Include only inside render/.
#include "render/overlay.h"
#include "render/passes/scene_passes.h"

namespace hs::render {

SceneTargets addSkyPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets);
SceneTargets addGridPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets);
SceneTargets addOverlayPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const SceneTargets& targets,
                    const Overlay& overlay);

}  // namespace hs::render
