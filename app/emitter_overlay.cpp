#include "app/emitter_overlay.h"

#include <cmath>

#include "app/overlay_shapes.h"
#include "particles/bounds.h"
#include "scene/particle_world.h"

namespace hs::app {
namespace {

constexpr double kStarPixels = 9.0, kArrowPixels = 60.0;

// Two unit vectors across `axis` (unit).
void across(const glm::dvec3& axis, glm::dvec3& u, glm::dvec3& v) {
  u = glm::normalize(glm::cross(axis, std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
  v = glm::cross(axis, u);
}

void star(render::Overlay& o, const glm::dvec3& p, double s, const glm::vec4& col) {
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 a(0.0);
    a[i] = s;
    o.line(p - a, p + a, col);
  }
}

// Great circles of a sphere: what a sphere looks like in lines.
void sphere(render::Overlay& o, const glm::dvec3& c, double r, const glm::vec4& col) {
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  circle(o, c, x, y, r, col, 48);
  circle(o, c, x, z, r, col, 48);
  circle(o, c, y, z, r, col, 48);
}

}  // namespace

void emitterGlyph(render::Overlay& o, const scene::SceneState& state, scene::EntityId id,
                  const render::RenderView& view, const glm::vec4& col, bool selected) {
  const std::optional<particles::EmitterDesc> placed = scene::emitterInWorld(state, id);
  if (!placed) return;
  const particles::EmitterDesc& d = *placed;
  const glm::dvec3 p = d.origin;
  const double px = worldPerPixels(view, p, 1.0);
  if (px <= 0.0) return;
  const double dl = glm::length(d.direction);
  const glm::dvec3 axis = dl > 0.0 ? d.direction / dl : glm::dvec3(0, 0, 1);
  glm::dvec3 u, v;
  across(axis, u, v);
  using S = particles::Shape;
  switch (d.shape) {
    case S::Point:
    case S::Mesh: star(o, p, kStarPixels * px, col); break;
    case S::Box: box(o, glm::dmat4(1.0), p - d.boxHalf, p + d.boxHalf, col); break;
    case S::Sphere: sphere(o, p, d.radius, col); break;
    case S::Disc: circle(o, p, u, v, d.radius, col, 48); break;
    case S::Cone: {
      circle(o, p, u, v, d.radius, col, 48);
      // The rim's particles lean out by the cone's angle.
      const double lean = glm::radians(d.coneAngleDeg), len = kArrowPixels * px;
      for (int i = 0; i < 4; ++i) {
        const double a = i * M_PI / 2.0;
        const glm::dvec3 radial = u * std::cos(a) + v * std::sin(a), rim = p + radial * d.radius;
        o.line(rim, rim + (std::cos(lean) * axis + std::sin(lean) * radial) * len, col);
      }
      break;
    }
    case S::Terrain: {
      // The area over the ground at the origin's height, and the height it reaches above.
      const glm::dvec3 h(d.boxHalf.x, d.boxHalf.y, 0.0);
      box(o, glm::dmat4(1.0), p - h, p + h, col);
      for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2) {
          const glm::dvec3 c = p + glm::dvec3(sx * d.boxHalf.x, sy * d.boxHalf.y, 0.0);
          o.line(c, c + glm::dvec3(0, 0, d.boxHalf.z), col);
        }
      break;
    }
  }
  // The direction (the shape's normal when along_normal: no single arrow).
  if (!d.alongNormal) {
    const double len = kArrowPixels * px;
    const glm::dvec3 tip = p + axis * len;
    o.line(p, tip, col);
    o.triangle(tip + axis * (8.0 * px), tip + u * (4.0 * px), tip - u * (4.0 * px), col);
    if (selected && d.spreadDeg > 0.0) {
      const double s = glm::radians(std::min(d.spreadDeg, 179.0));
      const glm::vec4 faint(col.r, col.g, col.b, col.a * 0.5f);
      const glm::dvec3 centre = p + axis * (len * std::cos(s));
      for (int i = 0; i < 8; ++i) {
        const double a = i * M_PI / 4.0;
        o.line(p, centre + (u * std::cos(a) + v * std::sin(a)) * (len * std::sin(s)), faint);
      }
      circle(o, centre, u, v, len * std::sin(s), faint, 32);
    }
  }
  if (selected) {
    // The renderer's bound at the shown time (what decides that it is out of view).
    scene::ParticleWorld world(state);
    const particles::SurfaceSampler* surface = d.shape == S::Mesh ? world.inputs(d, false).surface : nullptr;
    const auto b = scene::placedBound(*scene::placedEmitter(state, id), state.time.seconds, &world, surface);
    if (b) sphere(o, p + b->bound.centre, b->bound.radius, glm::vec4(col.r, col.g, col.b, col.a * 0.25f));
  }
}

}  // namespace hs::app
