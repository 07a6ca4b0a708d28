#include "particles/bounds.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hs::particles {

namespace {

struct SpeedTerms {
  double v0 = 0.0, wind = 0.0, accel = 0.0;
};
SpeedTerms terms(const EmitterDesc& e) {
  SpeedTerms s;
  s.wind = glm::length(e.wind);
  for (const WindKey& k : e.windKeys) s.wind = std::max(s.wind, glm::length(k.wind));
  s.v0 = std::max(std::abs(e.speedMin), std::abs(e.speedMax));
  s.accel = glm::length(e.gravity) + e.turbulence * kCurlNoiseBound;
  return s;
}

}  // namespace

double speedBound(const EmitterDesc& e, double age) {
  const SpeedTerms s = terms(e);
  double v = std::max(s.v0, s.wind) + s.accel * std::max(0.0, age);
  if (e.drag > 0.0) v = std::min(v, std::max(s.v0, s.wind + s.accel / e.drag));
  return v;
}

double travelBound(const EmitterDesc& e, double age) {
  const double tau = std::max(0.0, age);
  const SpeedTerms s = terms(e);
  // Both speed bounds hold for every tau; the travel is their integral.
  double d = std::max(s.v0, s.wind) * tau + 0.5 * s.accel * tau * tau;
  if (e.drag > 0.0) d = std::min(d, std::max(s.v0, s.wind + s.accel / e.drag) * tau);
  return d;
}

std::optional<ParticleBound> particleBound(const EmitterDesc& e, bool moves,
                                           std::optional<std::pair<double, double>> groundRange,
                                           const SurfaceSampler* surface) {
  if (moves && e.space == Space::World) return std::nullopt;
  ParticleBound b;
  switch (e.shape) {
    case Shape::Point: break;
    case Shape::Box: b.radius = glm::length(e.boxHalf); break;
    case Shape::Sphere:
    case Shape::Disc:
    case Shape::Cone: b.radius = e.radius; break;  // a cone's particles start on its base disc
    case Shape::Mesh: {
      const auto box = surface ? surface->box() : std::nullopt;
      if (!box) return std::nullopt;
      b.centre = 0.5 * (box->first + box->second);
      b.radius = 0.5 * glm::length(box->second - box->first);
      break;
    }
    case Shape::Terrain: {
      if (!groundRange) return std::nullopt;
      const double z0 = groundRange->first - e.origin.z, z1 = groundRange->second - e.origin.z + e.boxHalf.z;
      b.centre = {0.0, 0.0, 0.5 * (z0 + z1)};
      b.radius = glm::length(glm::dvec3(e.boxHalf.x, e.boxHalf.y, 0.5 * (z1 - z0)));
      break;
    }
  }
  b.radius += travelBound(e, e.lifetimeMax);
  if (!std::isfinite(b.radius)) return std::nullopt;
  return b;
}

}  // namespace hs::particles
