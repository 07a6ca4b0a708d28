// Atmosphere between a surface and the eye, the same for meshes, terrain
// and the sky (scene_state.h FogMode; docs/rendering.md "Fog"). Built as a
// variant: FOG_DEPTH_CUE or FOG_HEIGHT; without either (fog off) applyFog
// returns its colour and the block below does not exist.
//
// Depth cue (the survey's): the surface keeps f = min(1, 1/(k1 + k2·d)) of
// its colour, the rest is fog colour.
// Exponential height fog: density ρ(z) = ρ0·exp(−b·(z − h)). Along the ray
// from the eye (height z0) over distance d with height change Δz the optical
// depth is, exactly,
//   τ = ρ0·d·exp(−b·(z0 − h)) · (1 − exp(−b·Δz)) / (b·Δz)
// whose last factor tends to 1 as b·Δz → 0 (a horizontal ray, or no
// falloff): taken from its series there, so horizontal rays are stable.
// Exponents are clamped so extreme densities and falloffs stay finite.
#ifndef HS_FOG_GLSL
#define HS_FOG_GLSL
#include "frame_blocks.glsl"

#if defined(FOG_DEPTH_CUE) || defined(FOG_HEIGHT)
layout(std140, binding = 8) uniform FogBlock {
  vec4 colour;   // rgb
  vec4 params;   // x: k1, y: k2, z: density, w: height falloff
  vec4 height;   // x: fog height relative to the frame origin
} fog;

// (1 − e^(−x)) / x, with its series near 0.
float fogExpRatio(float x) {
  if (abs(x) < 1e-3) return 1.0 - x * 0.5 + x * x / 6.0;
  return (1.0 - exp(-clamp(x, -60.0, 60.0))) / x;
}

// How much of the surface's colour reaches the eye, along `p` (eye space:
// world axes, relative to the eye) over distance `d`.
float fogTransmittance(vec3 p, float d) {
#if defined(FOG_DEPTH_CUE)
  return min(1.0, 1.0 / max(fog.params.x + fog.params.y * d, 1e-6));
#else
  float b = fog.params.w;
  float z0 = view.eyeOffset.z - fog.height.x;  // the eye above the fog height
  float dz = d > 0.0 ? p.z * (d / max(length(p), 1e-20)) : 0.0;
  float tau = fog.params.z * d * exp(clamp(-b * z0, -60.0, 60.0)) * fogExpRatio(b * dz);
  return exp(-clamp(tau, 0.0, 1e4));
#endif
}

vec3 applyFog(vec3 color, vec3 p) {
  float t = fogTransmittance(p, length(p));
  return mix(fog.colour.rgb, color, t);
}

// The sky: a direction seen to `distance` (the far clip; depth cueing
// reaches its limit there, height fog integrates to it).
vec3 applySkyFog(vec3 color, vec3 dir, float distance) {
  float t = fogTransmittance(dir, distance);
  return mix(fog.colour.rgb, color, t);
}
#else
vec3 applyFog(vec3 color, vec3 p) { return color; }
vec3 applySkyFog(vec3 color, vec3 dir, float distance) { return color; }
#endif

#endif
