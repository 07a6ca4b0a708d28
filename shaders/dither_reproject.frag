#version 450 core
// Error diffusion in a stereo pair (render/passes/stylised_passes.h): for
// each pixel of the second eye, the first eye's dithered output where the
// first eye sees the same surface (this pixel reprojected through its depth
// into the first eye, not occluded there by more than 2 % of the distance,
// in frame): alpha 1 and the level; elsewhere 0 (the second eye diffuses
// on its own). The error diffusion then takes the level where alpha is 1
// and passes on its error, so a surface shows the same pattern in both eyes.
layout(binding = 0) uniform sampler2D uDepth;           // this eye's, reversed-Z
layout(binding = 1) uniform sampler2D uFirstDepth;
layout(binding = 2) uniform sampler2D uFirstDithered;
uniform mat4 uThisToFirst;  // this eye's window (NDC x, y; depth) to the first eye's clip space
layout(location = 0) out vec4 outForced;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const ivec2 size = textureSize(uDepth, 0);
  outForced = vec4(0.0);
  // Depth 0 is the far plane (the sky): still a point, far away.
  const float depth = max(texelFetch(uDepth, px, 0).r, 1e-9);
  const vec4 clip = uThisToFirst * vec4((vec2(px) + 0.5) / vec2(size) * 2.0 - 1.0, depth, 1.0);
  if (clip.w <= 0.0) return;
  const vec3 ndc = clip.xyz / clip.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  if (uv.x < 0.0 || uv.y < 0.0 || uv.x >= 1.0 || uv.y >= 1.0) return;
  const ivec2 at = ivec2(uv * vec2(textureSize(uFirstDepth, 0)));
  if (texelFetch(uFirstDepth, at, 0).r > ndc.z * 1.02 + 1e-9) return;  // nearer there: occluded
  outForced = vec4(texelFetch(uFirstDithered, at, 0).rgb, 1.0);
}
