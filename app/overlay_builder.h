#pragma once
// The viewport's non-gizmo overlays: selection bounds and the glyphs of
// entities that have no geometry (cameras, lights, empties), sized in screen
// pixels so they read the same at any distance.
#include <vector>

#include <glm/glm.hpp>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/scene_state.h"

namespace hs::app {

// Overlays are drawn into the renderer's linear HDR buffer, before exposure
// and the tone curve (ACES fit or none, SceneSettings::tonemap). This returns
// the value that comes out of that chain as `display` (linear 0..1), so
// handle colours stay exact whatever the scene's exposure and tone mapping.
glm::vec4 overlayColor(const glm::vec3& display, float alpha, const scene::SceneSettings& settings);

void buildSceneOverlay(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                       const render::RenderView& view, render::Overlay& out);

// The camera/light/empty whose glyph centre lies within `radiusPixels` of
// `pixel` (nearest first), or kNoEntity. Meshes are picked by the renderer.
scene::EntityId pickGlyph(const scene::SceneState& state, const render::RenderView& view, const glm::dvec2& pixel,
                          double radiusPixels = 12.0);

// Distance in pixels from `p` to the segment a-b.
double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b);

}  // namespace hs::app
