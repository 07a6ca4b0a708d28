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
//
// Units: the model gives luminance in cd/m²; scene radiance is that times
// the lights' scene unit, scene::sceneUnitsPerNit() (scene/light_units.h),
// so sun and sky are in one physical unit (docs/rendering.md, "Sky and
// environment").
#include <glm/glm.hpp>

namespace hs::render {

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

  // Scene radiance (linear sRGB, cd/m² x sceneUnitsPerNit()) seen looking along
  // unit `dir`. Below the horizon: the ground, a diffuse surface of
  // `groundAlbedo` under a uniform sky of the zenith's radiance, blended
  // into the horizon over the first 3 degrees.
  glm::dvec3 radiance(const glm::dvec3& dir) const;
};

// CIE xyY (Y in cd/m²) to linear sRGB (Rec. 709 primaries, D65).
glm::dvec3 xyYToLinearSrgb(const glm::dvec3& xyY);

}  // namespace hs::render
