#pragma once
// Preetham, Shirley and Smits' analytic daylight model ("A Practical
// Analytic Model for Daylight", SIGGRAPH 1999): the sky's luminance and
// chromaticity as Perez functions of the view's zenith angle and its angle
// to the sun, with coefficients linear in the turbidity. Chosen over
// Hosek-Wilkie because it is closed-form (a few dozen published constants,
// no coefficient tables to carry), cheap enough to evaluate per pixel, and
// the same few numbers drive the sky pass, the environment cube and the
// CPU reference the tests integrate. Its known weakness (too bright and
// too red near the horizon at low sun) is accepted for a film preview.
//
// GL-free: shaders/sky_model.glsl evaluates the same function from the
// coefficients this computes (uniforms), and tests/benchmarks call
// radiance() as the reference.
#include <glm/glm.hpp>

namespace hs::render {

// Scene radiance per cd/m² of sky luminance: the one place where the
// model's physical units meet the renderer's. It is the exposure 1/(1.2 x
// 2^EV100) at EV100 = 14.3 (a sunny day: the zenith at about 0.3 at 45
// degrees of sun, where the gradient sky's zenith was), chosen before the
// lights' scene unit (scene/light_units.h, EV100 15.2) existed. It is not
// tied to that unit yet: the lights fold the BRDF's 1/pi into their
// intensity, so tying only this would upset the sun/sky balance; both are
// to change together (docs/rendering.md).
inline constexpr double kSkyRadianceScale = 4.0e-5;

struct PreethamSky {
  glm::dvec3 sunDir{0.0, 0.0, 1.0};  // unit, towards the sun (world, z up)
  double sunFade = 1.0;              // 1 with the sun up, to 0 at 12 degrees below the horizon
  // Perez coefficients A..E, each for (Y, x, y).
  glm::dvec3 perez[5];
  glm::dvec3 zenith{0.0};            // Y (kcd/m²), x, y at the zenith
  glm::dvec3 normaliser{1.0};        // 1 / F(0, theta_sun) per channel
  double groundAlbedo = 0.2;
  glm::dvec3 zenithRgb{0.0};         // scene radiance at the zenith (the ground's light)

  // `sunDir` need not be unit; a zero vector means no sun (the sky of a
  // sun 45 degrees up in the south, so a scene without one still has a sky).
  static PreethamSky make(glm::dvec3 sunDir, double turbidity, double groundAlbedo);

  // Scene radiance (linear sRGB, x kSkyRadianceScale) seen looking along
  // unit `dir`. Below the horizon: the ground, a diffuse surface of
  // `groundAlbedo` under a uniform sky of the zenith's radiance, blended
  // into the horizon over the first 3 degrees.
  glm::dvec3 radiance(const glm::dvec3& dir) const;
};

// CIE xyY (Y in cd/m²) to linear sRGB (Rec. 709 primaries, D65).
glm::dvec3 xyYToLinearSrgb(const glm::dvec3& xyY);

}  // namespace hs::render
