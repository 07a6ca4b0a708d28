#pragma once
// Camera paths and motion in the viewport: each camera path's spline with
// its points (the spatial keys) and where its progress keys put the camera,
// and for the selected entities animated by translation keys, their motion
// over the sequence's range with a marker at each key. Drawn through
// render::Overlay (depth-tested, so the scene hides what is behind it).
#include <vector>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/scene_state.h"
#include "sequencer/sequence.h"

namespace hs::app {

void buildTimelineOverlay(const scene::SceneState& base, const sequencer::CompiledSequence& compiled,
                          const std::vector<scene::EntityId>& selection, const render::RenderView& view,
                          render::Overlay& out);

}  // namespace hs::app
