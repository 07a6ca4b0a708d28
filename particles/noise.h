#pragma once
// Curl noise for turbulence (docs/particles.md, "Turbulence"): a
// divergence-free vector field, a pure function of position and time, from
// three gradient-noise potentials psi_i (3D Perlin-style noise with quintic
// fade and analytic derivatives; gradients from the 32-bit hash of rng.h,
// so a shader computes the same field):
//     curl psi = (d psi3/dy - d psi2/dz, d psi1/dz - d psi3/dx, d psi2/dx - d psi1/dy)
// Time moves the sample point through the noise along a fixed direction.
#include <cstdint>

#include <glm/vec3.hpp>

namespace hs::particles {

struct NoiseSample {
  double value = 0.0;
  glm::dvec3 gradient{0.0};
};

// Gradient noise in about [-1, 1] with its exact gradient.
NoiseSample gradientNoise(const glm::dvec3& p, uint32_t seed);

// The curl of the three potentials at p (noise space).
glm::dvec3 curlNoise(const glm::dvec3& p, uint32_t seed);

// The turbulence acceleration at position x (metres, emitter-relative) and
// scene time t: strength * curlNoise(x * frequency + t * evolution * d).
glm::dvec3 turbulenceAt(const glm::dvec3& x, double t, double strength, double frequency, double evolution,
                        uint32_t seed);

}  // namespace hs::particles
