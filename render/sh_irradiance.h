#pragma once
// Irradiance as 9 spherical-harmonic coefficients (Ramamoorthi and
// Hanrahan, "An Efficient Representation for Irradiance Environment Maps",
// 2001): the CPU side of what shaders/env_sh.comp computes from the sky
// cube, and the references the tests and bench/render/bench_environment
// check it against. GL-free.
#include <array>
#include <functional>

#include <glm/glm.hpp>

namespace hs::render {

using RadianceFn = std::function<glm::dvec3(const glm::dvec3& dir)>;

// Real SH basis Y_lm(dir) for l = 0..2 (order (0,0), (1,-1), (1,0), (1,1),
// (2,-2), (2,-1), (2,0), (2,1), (2,2)), dir unit.
std::array<double, 9> shBasis(const glm::dvec3& dir);

// GL cube map conventions (faces +X -X +Y -Y +Z -Z, texel centres): the
// direction through texel (x, y) of `face` and its solid angle.
glm::dvec3 cubeTexelDirection(int face, int x, int y, int size);
double cubeTexelSolidAngle(int x, int y, int size);

// Radiance coefficients L_lm from the texel centres of a size^2 x 6 cube
// of `radiance`, weighted by solid angle (what env_sh.comp does).
std::array<glm::dvec3, 9> projectCube(const RadianceFn& radiance, int size);

// The light a white Lambertian surface of normal n reflects, E(n) / pi,
// from radiance coefficients, using bands 0..maxBand (2: all nine).
glm::dvec3 shIrradiance(const std::array<glm::dvec3, 9>& L, const glm::dvec3& n, int maxBand = 2);

// The same by brute force: the integral of radiance x cos over the
// hemisphere around n, midpoint rule on thetaSteps x 2 thetaSteps cells, / pi.
glm::dvec3 bruteForceIrradiance(const RadianceFn& radiance, const glm::dvec3& n, int thetaSteps = 96);

}  // namespace hs::render
