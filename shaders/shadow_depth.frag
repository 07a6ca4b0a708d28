#version 450 core
// Shadow maps hold depth only (the draw sources' Depth variant, render/draw_source.h). Variant
// ALPHA_CUTOUT, for submeshes whose material cuts out (foliage cards): the
// fragments mesh.frag drops (opacity x base colour alpha under the
// threshold) are dropped here too, so the shadow has the card's holes.
// The same variant casts translucent surfaces (opacity under 1, drawn by
// the transparency path): a share of the fragments equal to the opacity
// casts, chosen by a hash of the texel and depth (hashed alpha, after
// Wyman & McGuire 2017), so the filtered shadow lets about 1 - opacity of
// the light through, and two layers (a glass sphere's near and far side)
// pass different texels, about (1 - a)^2. A pure function of the frame:
// the same shadow every render.
// INSTANCED: an instanced source's caster drops the pixels its fade
// drops in the views (instance_fade.glsl), so its shadow fades with it.
#ifdef INSTANCED
#include "instance_fade.glsl"
#endif
#ifdef ALPHA_CUTOUT
#include "mesh_uv.glsl"
in vec2 vUv;
layout(binding = 0) uniform sampler2D uBaseColorTexture;
uniform vec4 uCutout;  // x: opacity, y: threshold, z: 1 with a base colour texture, w: 1 translucent (hashed)

// A uniform value in [0, 1) per texel and depth (integer hash, lowbias32).
float texelHash() {
  uint h = uint(gl_FragCoord.x) * 0x8DA6B343u ^ uint(gl_FragCoord.y) * 0xD8163841u ^ floatBitsToUint(gl_FragCoord.z);
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0 / 16777216.0);
}
#endif

void main() {
#ifdef INSTANCED
  instanceFadeDiscard();
#endif
#ifdef ALPHA_CUTOUT
  float alpha = uCutout.x * (uCutout.z > 0.5 ? texture(uBaseColorTexture, meshUv(vUv)).a : 1.0);
  if (alpha < (uCutout.w > 0.5 ? texelHash() : uCutout.y)) discard;
#endif
}
