// Light from the sky and the surroundings (everything but the direct
// lights). With the gradient sky: a hemisphere between the ground and the
// sky's zenith colour. With the analytic sky (frame.environment.x = 1):
// image-based light with no bake (docs/rendering.md, "Sky and
// environment"): diffuse from 9 spherical-harmonic coefficients of the
// sky's irradiance, specular from a GGX-prefiltered cube read at the
// surface's roughness with Karis's analytic split-sum BRDF; both made by
// the environment pass when the sun or the sky settings change.
#ifndef HS_ENVIRONMENT_GLSL
#define HS_ENVIRONMENT_GLSL
#include "frame_blocks.glsl"
#include "surface.glsl"

layout(std140, binding = 6) uniform EnvironmentBlock {
  vec4 sh[9];     // rgb: E(n)/pi coefficients (basis order of render/sh_irradiance.h)
  vec4 params;    // x: the specular cube's last mip level (roughness 1)
} env;
layout(binding = 12) uniform samplerCube uEnvSpecular;

vec3 shIrradiance(vec3 n) {
  return env.sh[0].rgb * 0.282095 + env.sh[1].rgb * (0.488603 * n.y) + env.sh[2].rgb * (0.488603 * n.z) +
         env.sh[3].rgb * (0.488603 * n.x) + env.sh[4].rgb * (1.092548 * n.x * n.y) +
         env.sh[5].rgb * (1.092548 * n.y * n.z) + env.sh[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0)) +
         env.sh[7].rgb * (1.092548 * n.x * n.z) + env.sh[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y));
}

// Karis, "Physically Based Shading on Mobile" (2014): the split sum's
// scale and bias for F0 as a fit of roughness and N.V, instead of a LUT.
vec3 envBrdfApprox(vec3 f0, float roughness, float ndv) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * ndv)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  return f0 * ab.x + ab.y;
}

vec3 imageBasedLighting(Surface s) {
  vec3 irradiance = max(shIrradiance(s.normal), vec3(0.0));
  if (s.model != MODEL_PBR) return s.albedo * irradiance;
  float ndv = max(dot(s.normal, s.view), 1e-4);
  vec3 f0 = mix(vec3(0.16 * s.specular * s.specular), s.albedo, s.metallic);
  vec3 brdf = envBrdfApprox(f0, s.roughness, ndv);
  vec3 r = reflect(-s.view, s.normal);
  vec3 prefiltered = textureLod(uEnvSpecular, r, s.roughness * env.params.x).rgb;
  vec3 diffuse = s.albedo * (1.0 - s.metallic) * (vec3(1.0) - brdf);
  return diffuse * irradiance + prefiltered * brdf;
}

vec3 ambientLighting(Surface s) {
  if (frame.environment.x > 0.5) return imageBasedLighting(s);
  float up = s.normal.z * 0.5 + 0.5;
  return s.albedo * mix(frame.groundColor.rgb, frame.skyZenith.rgb, up) * frame.params.x;
}

#endif
