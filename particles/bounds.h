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

// The sphere holding the positions of every particle of `e` at any time
// (sizes not included: a draw adds its sprite's or mesh's reach). nullopt
// when none can be given: a mesh shape without its surface's box
// (`surface`, the evaluator's SurfaceSampler), a world-space emitter whose
// entity moves (`moves`), or a terrain shape without the ground's height
// range (`groundRange`, world z min and max).
std::optional<ParticleBound> particleBound(const EmitterDesc& e, bool moves = false,
                                           std::optional<std::pair<double, double>> groundRange = std::nullopt,
                                           const SurfaceSampler* surface = nullptr);

}  // namespace hs::particles
