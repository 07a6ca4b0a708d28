// How much of a light reaches a point (1: lit, 0: in shadow).
// docs/rendering.md "Shadows"; the C++ side is render/passes/shadow_passes.cpp
// (the sun) and render/passes/local_shadow_pass.cpp (spot and point lights).
//
// The sun: cascaded shadow maps in one depth texture array (texture unit 8),
// matrices in ShadowBlock (binding 5), relative to the frame origin like
// every other position, so both eyes of a stereo pair read the same maps.
// The cascade is the first (finest) whose map holds the point with room for
// the filter kernel: chosen from the point alone, so both eyes choose alike.
// Depth in the maps is 1 on the sun's side; a point is lit where its depth
// is at least the stored one.
#ifndef HS_SHADOWS_GLSL
#define HS_SHADOWS_GLSL
#include "frame_blocks.glsl"

layout(std140, binding = 5) uniform ShadowBlock {
  mat4 sunCascade[4];    // frame-relative position -> (u, v, depth)
  vec4 sunTexelMetres;   // world size of one texel, per cascade
  vec4 sunParams;        // x: cascade count (0: no sun shadow), y: PCF radius, z: 1 / map size
  vec4 localParams;      // x: entries in LocalShadowBlock (0: none, not bound), y: 1 / layer size, z: PCF radius
} shadow;

layout(binding = 8) uniform sampler2DArrayShadow uSunShadowMap;

// Spot and point lights (render/local_shadows.h): one entry per light of the
// light buffer; a spot's map is one layer of uLocalShadowMaps, a point
// light's cube six (+X, -X, +Y, -Y, +Z, -Z), each a perspective view from
// the light with depth = near / distance (1 near the light).
struct LocalShadow {
  mat4 faces[6];   // frame-relative position -> (u w, v w, depth w, w) of the face's map
  vec4 params;     // x: first layer (-1: no map), y: faces, z: texel size at 1 m, w: the light's share of the layer
};
layout(std430, binding = 11) readonly buffer LocalShadowBlock { LocalShadow localShadows[]; };
layout(binding = 16) uniform sampler2DArrayShadow uLocalShadowMaps;

// Bias, in texels of the cascade: the receiver is moved this far along its
// normal (more where the light grazes it) before the lookup, which keeps
// lit surfaces from shadowing themselves (acne) without the peter-panning
// of a large depth offset. The casters also carry a slope-scaled polygon
// offset (shadow_passes.cpp).
const float kShadowNormalOffsetTexels = 1.5;

float sunVisibility(vec3 p, vec3 n) {
  int count = int(shadow.sunParams.x);
  if (count == 0) return 1.0;
  vec3 q = p + view.eyeOffset.xyz;  // eye space -> relative to the frame origin
  float cosL = clamp(dot(n, frame.sunDir.xyz), 0.0, 1.0);
  float slope = sqrt(1.0 - cosL * cosL);
  int radius = int(shadow.sunParams.y);
  float texel = shadow.sunParams.z;
  float margin = (float(radius) + 1.5) * texel;
  for (int i = 0; i < count; ++i) {
    vec3 offset = n * (shadow.sunTexelMetres[i] * kShadowNormalOffsetTexels * (0.5 + slope));
    vec3 s = (shadow.sunCascade[i] * vec4(q + offset, 1.0)).xyz;
    if (any(lessThan(s.xy, vec2(margin))) || any(greaterThan(s.xy, vec2(1.0 - margin))) || s.z < 0.0) continue;
    // PCF: (2r+1)^2 taps, each a bilinear 2x2 comparison.
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y)
      for (int x = -radius; x <= radius; ++x)
        lit += texture(uSunShadowMap, vec4(s.xy + vec2(x, y) * texel, float(i), min(s.z, 1.0)));
    float taps = float((2 * radius + 1) * (2 * radius + 1));
    return lit / taps;
  }
  return 1.0;  // beyond the last cascade
}

// Light `light` of the light buffer at eye-space point p with normal n.
// The face of a cube is the major axis of light -> point (the point alone
// decides: both eyes pick alike); the guard band around each face holds the
// kernel, so no tap crosses into the next face.
float localLightVisibility(int light, vec3 p, vec3 n) {
  if (light >= int(shadow.localParams.x)) return 1.0;
  vec4 info = localShadows[light].params;
  if (info.x < 0.0) return 1.0;
  vec3 q = p + view.eyeOffset.xyz;  // eye space -> relative to the frame origin
  vec3 fromLight = q - lights[light].position.xyz;
  int face = 0;
  if (info.y > 1.5) {
    vec3 a = abs(fromLight);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    face = axis * 2 + (fromLight[axis] < 0.0 ? 1 : 0);
  }
  float d = length(fromLight);
  vec3 l = -fromLight / max(d, 1e-4);
  float cosL = clamp(dot(n, l), 0.0, 1.0);
  float slope = sqrt(1.0 - cosL * cosL);
  vec3 offset = n * (info.z * d * kShadowNormalOffsetTexels * (0.5 + slope));
  vec4 c = localShadows[light].faces[face] * vec4(q + offset, 1.0);
  if (c.w <= 0.0) return 1.0;  // behind a spot: its beam does not reach there
  vec3 s = c.xyz / c.w;
  // Outside a spot's map is outside its cone (unlit anyway); nearer the
  // light than the near plane nothing casts.
  if (any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0)))) return 1.0;
  vec2 uv = s.xy * info.w;
  int radius = int(shadow.localParams.z);
  float texel = shadow.localParams.y;
  float layer = info.x + float(face);
  float lit = 0.0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x)
      lit += texture(uLocalShadowMaps, vec4(uv + vec2(x, y) * texel, layer, min(s.z, 1.0)));
  return lit / float((2 * radius + 1) * (2 * radius + 1));
}

#endif
