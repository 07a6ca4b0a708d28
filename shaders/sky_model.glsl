// Preetham's analytic daylight (render/sky_model.h has the model, the
// reasons and the units): the same function as PreethamSky::radiance, from
// the coefficients the renderer computes once per frame on the CPU.
#ifndef HS_SKY_MODEL_GLSL
#define HS_SKY_MODEL_GLSL

uniform vec3 uPerez[5];    // A..E, each for (Y, x, y)
uniform vec3 uZenith;      // Y (kcd/m²), x, y
uniform vec3 uNormaliser;  // 1 / F(0, theta_sun)
uniform vec4 uSkySun;      // xyz: towards the sun; w: fade below the horizon
uniform vec4 uSkyGround;   // rgb: the ground's radiance; w: scene radiance per cd/m²

vec3 perezF(float cosTheta, float gamma, float cosGamma) {
  return (1.0 + uPerez[0] * exp(uPerez[1] / cosTheta)) *
         (1.0 + uPerez[2] * exp(uPerez[3] * gamma) + uPerez[4] * (cosGamma * cosGamma));
}

vec3 xyYToLinearSrgb(vec3 c) {
  float y = max(c.y, 1e-6);
  float X = c.x / y * c.z, Y = c.z, Z = (1.0 - c.x - c.y) / y * c.z;
  return vec3(3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
              0.0557 * X - 0.2040 * Y + 1.0570 * Z);
}

// Scene radiance looking along unit `dir` (world, z up), without the sun's disc.
vec3 skyRadiance(vec3 dir) {
  float cosTheta = max(dir.z, 0.01);
  float cosGamma = clamp(dot(dir, uSkySun.xyz), -1.0, 1.0);
  vec3 ratio = perezF(cosTheta, acos(cosGamma), cosGamma) * uNormaliser;
  vec3 xyY = vec3(uZenith.y * ratio.y, uZenith.z * ratio.z, uZenith.x * ratio.x * 1000.0);
  vec3 sky = max(xyYToLinearSrgb(xyY), vec3(0.0)) * (uSkyGround.w * uSkySun.w);
  if (dir.z >= 0.0) return sky;
  return mix(sky, uSkyGround.rgb, smoothstep(0.0, 0.0523, -dir.z));
}

#endif
