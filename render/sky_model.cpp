#include "render/sky_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/light_units.h"

namespace hs::render {
namespace {

constexpr double kPi = std::numbers::pi;

// Perez et al.'s all-weather function, per channel.
glm::dvec3 perezF(const glm::dvec3 (&c)[5], double cosTheta, double gamma, double cosGamma) {
  const glm::dvec3 one(1.0);
  return (one + c[0] * glm::exp(c[1] / cosTheta)) *
         (one + c[2] * glm::exp(c[3] * gamma) + c[4] * (cosGamma * cosGamma));
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

glm::dvec3 xyYToLinearSrgb(const glm::dvec3& c) {
  const double x = c.x, y = std::max(c.y, 1e-6), Y = c.z;
  const double X = x / y * Y, Z = (1.0 - x - y) / y * Y;
  return {3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
          0.0557 * X - 0.2040 * Y + 1.0570 * Z};
}

PreethamSky PreethamSky::make(glm::dvec3 sunDir, double T, double groundAlbedo) {
  PreethamSky s;
  const double len = glm::length(sunDir);
  s.sunDir = len > 1e-9 && std::isfinite(len) ? sunDir / len : glm::normalize(glm::dvec3(0.0, -0.7071, 0.7071));
  T = std::clamp(std::isfinite(T) ? T : 3.0, 1.7, 10.0);
  s.groundAlbedo = std::clamp(std::isfinite(groundAlbedo) ? groundAlbedo : 0.2, 0.0, 1.0);
  // The fit is for a sun above the horizon: below it the sky keeps the
  // horizon sun's colours and fades out (civil twilight, roughly).
  s.sunFade = smoothstep(-0.21, 0.0, s.sunDir.z);
  const double thetaS = std::acos(std::clamp(s.sunDir.z, 0.0, 1.0));
  // Preetham et al., appendix A.2: coefficients for Y, x and y.
  const double a[5][3][2] = {
      {{0.1787, -1.4630}, {-0.0193, -0.2592}, {-0.0167, -0.2608}},
      {{-0.3554, 0.4275}, {-0.0665, 0.0008}, {-0.0950, 0.0092}},
      {{-0.0227, 5.3251}, {-0.0004, 0.2125}, {-0.0079, 0.2102}},
      {{0.1206, -2.5771}, {-0.0641, -0.8989}, {-0.0441, -1.6537}},
      {{-0.0670, 0.3703}, {-0.0033, 0.0452}, {-0.0109, 0.0529}},
  };
  for (int k = 0; k < 5; ++k)
    for (int c = 0; c < 3; ++c) s.perez[k][c] = a[k][c][0] * T + a[k][c][1];
  // Zenith luminance (kcd/m²) and chromaticity.
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * thetaS);
  const double Yz = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
  const double t1 = thetaS, t2 = t1 * t1, t3 = t2 * t1;
  const double xz = T * T * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * t1) +
                    T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * t1 + 0.00394) +
                    (0.11693 * t3 - 0.21196 * t2 + 0.06052 * t1 + 0.25886);
  const double yz = T * T * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * t1) +
                    T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * t1 + 0.00516) +
                    (0.15346 * t3 - 0.26756 * t2 + 0.06670 * t1 + 0.26688);
  s.zenith = {std::max(Yz, 0.0), xz, yz};
  s.normaliser = 1.0 / perezF(s.perez, 1.0, thetaS, std::cos(thetaS));
  s.zenithRgb = s.radiance({0.0, 0.0, 1.0});  // above the horizon: does not read zenithRgb
  return s;
}

glm::dvec3 PreethamSky::radiance(const glm::dvec3& dir) const {
  // Above the horizon the model; the horizon row (cos theta -> 0) is taken
  // at cos theta = 0.01 (the model's exp(B / cos theta) is 0 there anyway).
  const double cosTheta = std::max(dir.z, 0.01);
  const double cosGamma = std::clamp(glm::dot(dir, sunDir), -1.0, 1.0);
  const double gamma = std::acos(cosGamma);
  const glm::dvec3 ratio = perezF(perez, cosTheta, gamma, cosGamma) * normaliser;
  // Y in kcd/m² -> cd/m², chromaticity as the model gives it.
  const glm::dvec3 xyY(zenith.y * ratio.y, zenith.z * ratio.z, zenith.x * ratio.x * 1000.0);
  const glm::dvec3 sky = glm::max(xyYToLinearSrgb(xyY), glm::dvec3(0.0)) * (scene::sceneUnitsPerNit() * sunFade);
  if (dir.z >= 0.0) return sky;
  const glm::dvec3 ground = zenithRgb * groundAlbedo;
  return glm::mix(sky, ground, smoothstep(0.0, 0.0523, -dir.z));
}

}  // namespace hs::render
