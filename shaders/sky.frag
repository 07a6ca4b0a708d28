#version 450 core
// The sky behind everything: drawn last where the depth buffer is still
// clear, so covered pixels cost nothing. Two variants: the gradient
// (settings.sky = gradient) and Preetham's analytic sky (SKY_ANALYTIC,
// shaders/sky_model.glsl) with the sun's disc.
#include "fog.glsl"
#include "frame_blocks.glsl"
#ifdef SKY_ANALYTIC
#include "sky_model.glsl"
#endif
in vec2 vUv;
layout(location = 0) out vec4 outColor;

void main() {
  vec2 ndc = vUv * 2.0 - 1.0 - view.tanHalfFov.zw;  // the projection added the shift
  vec3 dirView = normalize(vec3(ndc * view.tanHalfFov.xy, -1.0));
  vec3 dir = mat3(view.invViewRotation) * dirView;
#ifdef SKY_ANALYTIC
  vec3 c = skyRadiance(dir);
  if (frame.sunDir.w > 0.5 && dir.z > 0.0) {
    // The sun's disc (0.27 degrees of radius, its rim softened by a fifth):
    // the radiance that gives the sun light's illuminance over the disc's
    // solid angle (colour / 6.8e-5 sr, in the sky's unit: both are scene
    // units), capped well inside half-float range.
    float cosGamma = dot(dir, frame.sunDir.xyz);
    float disc = smoothstep(cos(0.00465 * 1.2), cos(0.00465 * 0.8), cosGamma);
    c += min(frame.sunColor.rgb * (1.0 / 6.8e-5), vec3(30000.0)) * (disc * uSkySun.w);
  }
#else
  float z = dir.z;
  vec3 c;
  if (z >= 0.0)
    c = mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, pow(z, 0.55));
  else
    c = mix(frame.skyHorizon.rgb, frame.groundColor.rgb, 1.0 - pow(1.0 + z, 8.0));
  if (frame.sunDir.w > 0.5) {
    // A glow around the sun: its illuminance as a white diffuser shows it
    // (E/pi, the lights' unit since format 8), shaped by two lobes.
    float s = max(dot(dir, frame.sunDir.xyz), 0.0);
    c += frame.sunColor.rgb * (1.0 / 3.14159265) * (pow(s, 1200.0) * 8.0 + pow(s, 24.0) * 0.08);
  }
#endif
  // Fog (fog.glsl; nothing without it) as far as a sky is taken to be.
  outColor = vec4(applySkyFog(c, dir, 1.0e5), 1.0);
}
