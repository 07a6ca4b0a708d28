#version 450 core
// HDR linear scene -> display: exposure, optional ACES-fitted curve, sRGB
// encoding (done here, so any 8-bit target, the Qt widget's included, shows
// correct sRGB). When FXAA follows, luma goes to alpha for it; otherwise
// alpha is 1 (frames are opaque).
#include "common.glsl"
in vec2 vUv;
layout(binding = 0) uniform sampler2D uScene;
uniform float uExposure;
uniform bool uFilmic;
uniform bool uLumaInAlpha;
layout(location = 0) out vec4 outColor;

vec3 acesFitted(vec3 x) {
  // Narkowicz 2015 fit of the ACES RRT+ODT.
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

void main() {
  vec3 c = texture(uScene, vUv).rgb * uExposure;
  if (uFilmic) c = acesFitted(c);
  vec3 s = linearToSrgb(c);
  outColor = vec4(s, uLumaInAlpha ? dot(s, vec3(0.299, 0.587, 0.114)) : 1.0);
}
