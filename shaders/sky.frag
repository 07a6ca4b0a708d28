#version 450 core
// Sky gradient behind everything: drawn last where the depth buffer is
// still clear, so covered pixels cost nothing.
#include "fog.glsl"
#include "frame_blocks.glsl"
in vec2 vUv;
layout(location = 0) out vec4 outColor;

void main() {
  vec2 ndc = vUv * 2.0 - 1.0 - view.tanHalfFov.zw;  // the projection added the shift
  vec3 dirView = normalize(vec3(ndc * view.tanHalfFov.xy, -1.0));
  vec3 dir = mat3(view.invViewRotation) * dirView;
  float z = dir.z;
  vec3 c;
  if (z >= 0.0)
    c = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, pow(z, 0.55));
  else
    c = mix(frame.skyHorizon.rgb, frame.groundColor.rgb, 1.0 - pow(1.0 + z, 8.0));
  if (frame.sunDir.w > 0.5) {
    float s = max(dot(dir, frame.sunDir.xyz), 0.0);
    c += frame.sunColor.rgb * (pow(s, 1200.0) * 8.0 + pow(s, 24.0) * 0.08);
  }
  // Fog (fog.glsl; nothing without it) as far as a sky is taken to be.
  outColor = vec4(applySkyFog(c, dir, 1.0e5), 1.0);
}
