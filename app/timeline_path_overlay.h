#pragma once
// Camera paths and motion in the viewport: each camera path's spline with
// its points (the spatial keys), where its progress keys put the camera and
// where the camera is at `time` (a green diamond), for a selected path its
// look-at point; and for the selected entities animated by translation keys,
// their motion over the sequence's range with a marker at each key. Drawn
// through render::Overlay, on top of the scene (the selected point and its
// handles come from PathPointDrag).
#include <vector>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/scene_state.h"
#include "sequencer/sequence.h"

namespace hs::app {

void buildTimelineOverlay(const scene::SceneState& base, const sequencer::CompiledSequence& compiled,
                          const std::vector<scene::EntityId>& selection, double time, const render::RenderView& view,
                          render::Overlay& out);

}  // namespace hs::app
