#pragma once
// Where an emitter's particles can be, without evaluating one of them
// (docs/particles.md, "Bounds"): a sphere, relative to the emitter's origin,
// that holds every particle alive at any time. The renderer tests it
// against the frame's views first, so an emitter out of view costs nothing.
//
// Proven, not sampled: from the motion dv/dt = g + turbulence + k (w - v),
// |v|' <= G + T + k (W - |v|) (G = |g|, T the curl noise's bound times the
// strength, W the largest wind), so
//     |v(tau)| <= min( max(V0, W + (G + T) / k)   (k > 0),
//                      max(V0, W) + (G + T) tau )
// and a particle is at most the integral of that from where it was born,
// over a life of at most lifetime_max. A bounce keeps |v| or less
// (restitution and friction at most 1), sticking and killing stop it, so
// collisions only shorten the path. The curl noise's bound comes from its
// construction (noise.cpp: quintic fade, cube-edge gradients): each
// potential's partial derivative is at most 8.5, so |curl| <= 17 sqrt(3);
// the field's real maximum is several times smaller, so a turbulent
// emitter's bound is loose (it is still finite; far-away emitters are what
// it is for).
#include <optional>
#include <utility>

#include <glm/vec3.hpp>

#include "particles/emitter.h"
#include "particles/evaluate.h"

namespace hs::particles {

inline constexpr double kCurlNoiseBound = 17.0 * 1.7320508075688772;

struct ParticleBound {
  glm::dvec3 centre{0.0};  // relative to the emitter's origin
  double radius = 0.0;     // metres
};

// The fastest a particle can be at `age` seconds (what a velocity-stretched
// sprite's reach needs), and the farthest it moves from its birth position
// in that time.
double speedBound(const EmitterDesc& e, double age);
double travelBound(const EmitterDesc& e, double age);

// Where a world-space emitter on a moving entity was while the particles
// alive now were born (world coordinates, the box's corners).
struct OriginBox {
  glm::dvec3 lo{0.0}, hi{0.0};
};

// What a bound needs besides the emitter.
struct BoundInputs {
  // World space on a moving entity: its particles start where it was at
  // their birth. Without `birthOrigins` there is then no bound.
  bool moves = false;
  std::optional<OriginBox> birthOrigins{};
  std::optional<std::pair<double, double>> groundRange{};  // a terrain shape's ground: world z min and max
  const SurfaceSampler* surface = nullptr;                 // a mesh shape's surface (its box)
};

// The sphere holding the positions of every particle of `e` at any time
// (sizes not included: a draw adds its sprite's or mesh's reach). nullopt
// when none can be given: a mesh shape without its surface's box, a moving
// world-space emitter without its birth origins, a terrain shape without
// the ground's height range.
std::optional<ParticleBound> particleBound(const EmitterDesc& e, const BoundInputs& in = {});

// The emitter with its spawn values widened to every value between `lo`
// and `hi` (its spawn values with each keyed member at the smallest and the
// largest its track takes over the births that matter): particleBound,
// speedBound and its sizes then hold for particles whose spawn values a
// track set (EvaluatorInputs::spawnAt). Only what a bound reads is widened
// (speeds, sizes, radius, box); the rest stays.
EmitterDesc widenedForSpawn(const EmitterDesc& e, const SpawnValues& lo, const SpawnValues& hi);

}  // namespace hs::particles
