#pragma once
// Line shapes the viewport's overlays are drawn with (overlay_builder.h,
// emitter_overlay.h): screen-constant sizes, circles and boxes in world
// coordinates (double).
#include <glm/glm.hpp>

#include "render/overlay.h"
#include "render/render_view.h"

namespace hs::app {

// Screen-constant size: the world length of `pixels` at the depth of `p`;
// 0 if `p` is behind the camera.
double worldPerPixels(const render::RenderView& view, const glm::dvec3& p, double pixels);

// A circle about `c` of radius r in the plane of the unit vectors u, v.
void circle(render::Overlay& o, const glm::dvec3& c, const glm::dvec3& u, const glm::dvec3& v, double r,
            const glm::vec4& col, int segments = 32);

// The box [mn, mx] of a local frame placed by `world`.
void box(render::Overlay& o, const glm::dmat4& world, const glm::dvec3& mn, const glm::dvec3& mx,
         const glm::vec4& col);

}  // namespace hs::app
