#version 450 core
// Shadow maps hold depth only (render/passes/shadow_casters.cpp). Variant
// ALPHA_CUTOUT, for submeshes whose material cuts out (foliage cards): the
// fragments mesh.frag drops (opacity x base colour alpha under the
// threshold) are dropped here too, so the shadow has the card's holes.
#ifdef ALPHA_CUTOUT
in vec2 vUv;
layout(binding = 0) uniform sampler2D uBaseColorTexture;
uniform vec4 uCutout;  // x: opacity, y: threshold, z: 1 with a base colour texture
#endif

void main() {
#ifdef ALPHA_CUTOUT
  float alpha = uCutout.x * (uCutout.z > 0.5 ? texture(uBaseColorTexture, vUv).a : 1.0);
  if (alpha < uCutout.y) discard;
#endif
}
