#include "particles/noise.h"

#include <cmath>

#include "particles/rng.h"

namespace hs::particles {

namespace {

// A unit-ish gradient for a lattice corner: one of the 12 cube-edge
// directions (Perlin's improved noise), chosen by the hash.
glm::dvec3 cornerGradient(uint32_t ix, uint32_t iy, uint32_t iz, uint32_t seed) {
  const uint32_t h = hashU32(hashU32(hashU32(hashU32(seed) ^ ix) ^ iy) ^ iz);
  static constexpr double g[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                                      {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
  const auto& r = g[(h >> 8) % 12];
  return {r[0], r[1], r[2]};
}

}  // namespace

NoiseSample gradientNoise(const glm::dvec3& p, uint32_t seed) {
  const glm::dvec3 fl{std::floor(p.x), std::floor(p.y), std::floor(p.z)};
  // Lattice coordinates wrap modulo 2^32 (through int64: no overflow for any
  // sample point a scene can make, t * evolution included).
  const uint32_t ix = uint32_t(int64_t(fl.x)), iy = uint32_t(int64_t(fl.y)), iz = uint32_t(int64_t(fl.z));
  const glm::dvec3 f = p - fl;
  const glm::dvec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  const glm::dvec3 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);

  const glm::dvec3 ga = cornerGradient(ix, iy, iz, seed), gb = cornerGradient(ix + 1u, iy, iz, seed),
                   gc = cornerGradient(ix, iy + 1u, iz, seed), gd = cornerGradient(ix + 1u, iy + 1u, iz, seed),
                   ge = cornerGradient(ix, iy, iz + 1u, seed), gf = cornerGradient(ix + 1u, iy, iz + 1u, seed),
                   gg = cornerGradient(ix, iy + 1u, iz + 1u, seed), gh = cornerGradient(ix + 1u, iy + 1u, iz + 1u, seed);
  auto dot = [](const glm::dvec3& a, const glm::dvec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  const double va = dot(ga, f), vb = dot(gb, f - glm::dvec3(1, 0, 0)), vc = dot(gc, f - glm::dvec3(0, 1, 0)),
               vd = dot(gd, f - glm::dvec3(1, 1, 0)), ve = dot(ge, f - glm::dvec3(0, 0, 1)),
               vf = dot(gf, f - glm::dvec3(1, 0, 1)), vg = dot(gg, f - glm::dvec3(0, 1, 1)),
               vh = dot(gh, f - glm::dvec3(1, 1, 1));

  const double k0 = va, k1 = vb - va, k2 = vc - va, k3 = ve - va, k4 = va - vb - vc + vd, k5 = va - vc - ve + vg,
               k6 = va - vb - ve + vf, k7 = -va + vb + vc - vd + ve - vf - vg + vh;
  const glm::dvec3 g0 = ga, g1 = gb - ga, g2 = gc - ga, g3 = ge - ga, g4 = ga - gb - gc + gd, g5 = ga - gc - ge + gg,
                   g6 = ga - gb - ge + gf, g7 = -ga + gb + gc - gd + ge - gf - gg + gh;

  NoiseSample s;
  s.value = k0 + k1 * u.x + k2 * u.y + k3 * u.z + k4 * u.x * u.y + k5 * u.y * u.z + k6 * u.z * u.x +
            k7 * u.x * u.y * u.z;
  s.gradient = g0 + g1 * u.x + g2 * u.y + g3 * u.z + g4 * u.x * u.y + g5 * u.y * u.z + g6 * u.z * u.x +
               g7 * u.x * u.y * u.z +
               du * glm::dvec3(k1 + k4 * u.y + k6 * u.z + k7 * u.y * u.z, k2 + k5 * u.z + k4 * u.x + k7 * u.z * u.x,
                               k3 + k6 * u.x + k5 * u.y + k7 * u.x * u.y);
  return s;
}

glm::dvec3 curlNoise(const glm::dvec3& p, uint32_t seed) {
  const glm::dvec3 d1 = gradientNoise(p, hashU32(seed ^ 0x1u)).gradient;
  const glm::dvec3 d2 = gradientNoise(p, hashU32(seed ^ 0x2u)).gradient;
  const glm::dvec3 d3 = gradientNoise(p, hashU32(seed ^ 0x3u)).gradient;
  return {d3.y - d2.z, d1.z - d3.x, d2.x - d1.y};
}

glm::dvec3 turbulenceAt(const glm::dvec3& x, double t, double strength, double frequency, double evolution,
                        uint32_t seed) {
  if (strength == 0.0) return glm::dvec3(0.0);
  const glm::dvec3 drift{0.37, 0.59, 0.71};
  return strength * curlNoise(x * frequency + (t * evolution) * drift, seed);
}

}  // namespace hs::particles
