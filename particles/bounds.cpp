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

std::optional<ParticleBound> particleBound(const EmitterDesc& e, const BoundInputs& in) {
  const bool moved = in.moves && e.space == Space::World;
  if (moved && !in.birthOrigins) return std::nullopt;
  ParticleBound b;
  switch (e.shape) {
    case Shape::Point: break;
    case Shape::Box: b.radius = glm::length(e.boxHalf); break;
    case Shape::Sphere:
    case Shape::Disc:
    case Shape::Cone: b.radius = e.radius; break;  // a cone's particles start on its base disc
    case Shape::Mesh: {
      const auto box = in.surface ? in.surface->box() : std::nullopt;
      if (!box) return std::nullopt;
      b.centre = 0.5 * (box->first + box->second);
      b.radius = 0.5 * glm::length(box->second - box->first);
      break;
    }
    case Shape::Terrain: {
      if (!in.groundRange) return std::nullopt;
      const double z0 = in.groundRange->first - e.origin.z, z1 = in.groundRange->second - e.origin.z + e.boxHalf.z;
      b.centre = {0.0, 0.0, 0.5 * (z0 + z1)};
      b.radius = glm::length(glm::dvec3(e.boxHalf.x, e.boxHalf.y, 0.5 * (z1 - z0)));
      break;
    }
  }
  if (moved) {
    // Born around where the emitter was (evaluate.cpp): shifted by the
    // origin box's centre, grown by its half diagonal. A terrain shape's
    // height is the ground's (only x, y follow the origin); a mesh shape's
    // surface is another entity's, wherever this one was.
    glm::dvec3 shift = 0.5 * (in.birthOrigins->lo + in.birthOrigins->hi) - e.origin;
    glm::dvec3 half = 0.5 * (in.birthOrigins->hi - in.birthOrigins->lo);
    if (e.shape == Shape::Terrain) shift.z = half.z = 0.0;
    if (e.shape != Shape::Mesh) {
      b.centre += shift;
      b.radius += glm::length(half);
    }
  }
  b.radius += travelBound(e, e.lifetimeMax);
  if (!std::isfinite(b.radius) || !std::isfinite(b.centre.x) || !std::isfinite(b.centre.y) || !std::isfinite(b.centre.z))
    return std::nullopt;
  return b;
}

EmitterDesc widenedForSpawn(const EmitterDesc& e, const SpawnValues& lo, const SpawnValues& hi) {
  EmitterDesc w = e;
  // A pair's members move with its centre: the smallest minimum and the
  // largest maximum hold every draw.
  w.speedMin = std::min({e.speedMin, lo.speedMin, hi.speedMin});
  w.speedMax = std::max({e.speedMax, lo.speedMax, hi.speedMax});
  w.sizeMin = std::min({e.sizeMin, lo.sizeMin, hi.sizeMin});
  w.sizeMax = std::max({e.sizeMax, lo.sizeMax, hi.sizeMax});
  w.radius = std::max({std::abs(e.radius), std::abs(lo.radius), std::abs(hi.radius)});
  w.boxHalf = glm::max(glm::abs(e.boxHalf), glm::max(glm::abs(lo.boxHalf), glm::abs(hi.boxHalf)));
  return w;
}

}  // namespace hs::particles
