#include "render/sh_irradiance.h"

#include <cmath>
#include <numbers>

namespace hs::render {
namespace {
constexpr double kPi = std::numbers::pi;

// Integral of the solid angle from the cube face's centre to (x, y) on the
// face at distance 1 (Driscoll's closed form).
double areaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }
}  // namespace

std::array<double, 9> shBasis(const glm::dvec3& d) {
  return {0.282095,
          0.488603 * d.y,
          0.488603 * d.z,
          0.488603 * d.x,
          1.092548 * d.x * d.y,
          1.092548 * d.y * d.z,
          0.315392 * (3.0 * d.z * d.z - 1.0),
          1.092548 * d.x * d.z,
          0.546274 * (d.x * d.x - d.y * d.y)};
}

glm::dvec3 cubeTexelDirection(int face, int x, int y, int size) {
  const double s = 2.0 * (x + 0.5) / size - 1.0, t = 2.0 * (y + 0.5) / size - 1.0;
  glm::dvec3 d;
  switch (face) {
    case 0: d = {1.0, -t, -s}; break;
    case 1: d = {-1.0, -t, s}; break;
    case 2: d = {s, 1.0, t}; break;
    case 3: d = {s, -1.0, -t}; break;
    case 4: d = {s, -t, 1.0}; break;
    default: d = {-s, -t, -1.0}; break;
  }
  return glm::normalize(d);
}

double cubeTexelSolidAngle(int x, int y, int size) {
  const double inv = 1.0 / size;
  const double x0 = 2.0 * x * inv - 1.0, x1 = x0 + 2.0 * inv;
  const double y0 = 2.0 * y * inv - 1.0, y1 = y0 + 2.0 * inv;
  return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

std::array<glm::dvec3, 9> projectCube(const RadianceFn& radiance, int size) {
  std::array<glm::dvec3, 9> L{};
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec3 d = cubeTexelDirection(face, x, y, size);
        const glm::dvec3 r = radiance(d) * cubeTexelSolidAngle(x, y, size);
        const std::array<double, 9> b = shBasis(d);
        for (int k = 0; k < 9; ++k) L[k] += r * b[k];
      }
  return L;
}

glm::dvec3 shIrradiance(const std::array<glm::dvec3, 9>& L, const glm::dvec3& n, int maxBand) {
  // The clamped cosine's zonal coefficients A_l (pi, 2pi/3, pi/4), / pi.
  const double A[3] = {1.0, 2.0 / 3.0, 0.25};
  const std::array<double, 9> b = shBasis(n);
  glm::dvec3 e(0.0);
  for (int k = 0; k < 9; ++k) {
    const int band = k == 0 ? 0 : (k < 4 ? 1 : 2);
    if (band <= maxBand) e += L[k] * (A[band] * b[k]);
  }
  return e;
}

glm::dvec3 bruteForceIrradiance(const RadianceFn& radiance, const glm::dvec3& n, int thetaSteps) {
  // An orthonormal frame around n.
  const glm::dvec3 helper = std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), b = glm::cross(n, t);
  const int phiSteps = 2 * thetaSteps;
  const double dTheta = 0.5 * kPi / thetaSteps, dPhi = 2.0 * kPi / phiSteps;
  glm::dvec3 e(0.0);
  for (int i = 0; i < thetaSteps; ++i) {
    const double theta = (i + 0.5) * dTheta;
    const double w = std::cos(theta) * std::sin(theta) * dTheta * dPhi;
    for (int j = 0; j < phiSteps; ++j) {
      const double phi = (j + 0.5) * dPhi;
      const glm::dvec3 d = std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * b) + std::cos(theta) * n;
      e += radiance(d) * w;
    }
  }
  return e / kPi;
}

}  // namespace hs::render
