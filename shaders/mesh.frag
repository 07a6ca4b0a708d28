#version 450 core
// Meshes: the base colour (material x texture x instance tint), lit by
// lighting.glsl.
#include "lighting.glsl"

in vec3 vEyePos;
in vec3 vNormal;
in vec2 vUv;
flat in uint vObject;

uniform vec4 uBaseColor;       // linear
uniform bool uHasTexture;
layout(binding = 0) uniform sampler2D uAlbedo;  // sRGB texture: sampled as linear

layout(location = 0) out vec4 outColor;

void main() {
  vec4 albedo = uBaseColor * vec4(objects[vObject].tint.rgb, 1.0);
  if (uHasTexture) albedo *= texture(uAlbedo, vUv);
  vec3 n = normalize(vNormal);
  // Scans are often open surfaces seen from behind: light the side we see.
  if (!gl_FrontFacing) n = -n;
  outColor = vec4(lightSurface(albedo.rgb, vEyePos, n, 32.0, 0.15), albedo.a);
}
