// Direct light from the sun and the scene's point and spot lights on a
// surface. Light values are in scene units (scene/light_units.h): the sun's
// colour is its illuminance, a point or spot light's its luminous intensity
// (candela), divided here by the squared distance.
#ifndef HS_LIGHTS_GLSL
#define HS_LIGHTS_GLSL
#include "brdf.glsl"
#include "frame_blocks.glsl"
#include "shadows.glsl"
#ifdef LIGHTS_CLUSTERED
#include "light_clusters.glsl"
layout(std430, binding = 7) readonly buffer LightGrid { uint clusterCounts[]; };
layout(std430, binding = 9) readonly buffer LightIndexList { uint clusterLights[]; };
#endif

// Inverse square, windowed to exactly 0 at the range (Filament's and
// Unreal's (1 − (d/r)⁴)², smooth, no hard cut-off): a light list that drops
// a light beyond its range loses nothing (render/passes/light_culling.h relies on
// it). The 1 cm floor keeps a surface at the light finite.
float distanceAttenuation(float d, float range) {
  float x = d / range;
  float window = clamp(1.0 - x * x * x * x, 0.0, 1.0);
  return window * window / max(d * d, 1e-4);
}

// A spot's beam: 1 inside the inner cone, 0 outside the outer one, a smooth
// (squared) step on the cosine between them; 1 for a point light.
float spotAttenuation(Light light, vec3 l) {
  if (light.color.w < 1.5) return 1.0;
  float t = clamp(dot(-l, light.direction.xyz) * light.spot.x + light.spot.y, 0.0, 1.0);
  return t * t;
}

// The normal the shadow lookup offsets along: the side the light arrives
// on. Light a surface lets through (brdf.glsl, transmission) arrives on its
// far side: offset along the eye's side's normal, the lookup would lie
// behind the surface itself as the light sees it, in its own shadow.
vec3 visibilityNormal(Surface s, vec3 l) {
  return s.transmission > 0.0 && dot(s.normal, l) < 0.0 ? -s.normal : s.normal;
}

// Light `i` of the light buffer on surface `s`.
vec3 pointOrSpotLight(Surface s, int i) {
  vec3 toLight = lights[i].position.xyz - view.eyeOffset.xyz - s.position;
  float d = length(toLight);
  vec3 l = toLight / max(d, 1e-4);
  float atten = distanceAttenuation(d, lights[i].position.w) * spotAttenuation(lights[i], l);
  if (atten <= 0.0) return vec3(0.0);
  return reflectLight(s, l) * lights[i].color.rgb * atten * localLightVisibility(i, s.position, visibilityNormal(s, l));
}

vec3 directLighting(Surface s) {
  vec3 color = vec3(0.0);
  if (frame.sunDir.w > 0.5)
    color += reflectLight(s, frame.sunDir.xyz) * frame.sunColor.rgb *
             sunVisibility(s.position, visibilityNormal(s, frame.sunDir.xyz));
#ifdef LIGHTS_CLUSTERED
  // The lights of this pixel's cluster (light_clusters.glsl; fragment
  // shaders only: the tile comes from gl_FragCoord).
  ivec2 tile = clamp(ivec2(gl_FragCoord.xy * view.viewport.zw * vec2(LIGHT_TILES_X, LIGHT_TILES_Y)), ivec2(0),
                     ivec2(LIGHT_TILES_X - 1, LIGHT_TILES_Y - 1));
  float depth = -(mat3(view.viewRotation) * s.position).z;
  int cluster = lightClusterIndex(tile, lightSliceOf(depth));
  uint n = min(clusterCounts[cluster], uint(LIGHT_CLUSTER_CAP));
  uint base = uint(cluster) * uint(LIGHT_CLUSTER_CAP);
  for (uint k = 0u; k < n; ++k) color += pointOrSpotLight(s, int(clusterLights[base + k]));
#else
  // Every light of the frame (no light in view: none; the brute-force
  // reference of the tests and bench_lights; Gouraud's vertices).
  int count = int(frame.params.z);
  for (int i = 0; i < count; ++i) color += pointOrSpotLight(s, i);
#endif
  return color;
}

#endif
