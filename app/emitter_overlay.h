#pragma once
// A particle emitter in the viewport (docs/particles.md, "In the editor"):
// where its particles are born, drawn as lines at its world origin: a point
// as a small star, a box, a sphere as three great circles, a disc as its
// rim across the direction, a cone as its base rim and its opening, the
// terrain shape as its area's outline at the origin's height, a mesh shape
// as a star (its mesh entity shows the surface); and its direction as an
// arrow. Selected, also its spread (a cone of lines) and, faint, the
// sphere that holds every particle it can have (particles/bounds.h): what
// the renderer tests against the views to skip an emitter out of view.
#include <glm/glm.hpp>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/scene_state.h"

namespace hs::app {

void emitterGlyph(render::Overlay& o, const scene::SceneState& state, scene::EntityId id,
                  const render::RenderView& view, const glm::vec4& col, bool selected);

}  // namespace hs::app
