// How much of a light reaches a point (1: lit, 0: in shadow).
// docs/rendering.md "Shadows"; the C++ side is render/passes/shadow_passes.cpp.
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
} shadow;

layout(binding = 8) uniform sampler2DArrayShadow uSunShadowMap;

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

float lightVisibility(int light, vec3 p, vec3 n) { return 1.0; }

#endif
