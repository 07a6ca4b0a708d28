#version 450 core
// The depth-complexity view (render/oit.h addDepthComplexityPass): each
// pixel's count of translucent fragments in front of the opaque surface as
// a heat map, black for none, then blue (one) through green and yellow to
// red (the frame's deepest pixel). Written in place of the scene colour,
// divided by the exposure so the tone mapper shows the ramp's colours.
#include "abuffer.glsl"
uniform float uMaxCount;
uniform float uInvExposure;
layout(location = 0) out vec4 outColor;

vec3 heat(float t) {
  const vec3 stops[4] = vec3[](vec3(0.05, 0.1, 0.9), vec3(0.1, 0.8, 0.2), vec3(0.95, 0.85, 0.1), vec3(0.9, 0.1, 0.05));
  const float x = clamp(t, 0.0, 1.0) * 3.0;
  const int i = min(int(x), 2);
  return mix(stops[i], stops[i + 1], x - float(i));
}

void main() {
  const uint n = imageLoad(uABufferCounts, ivec2(gl_FragCoord.xy)).x;
  const vec3 c = n == 0u ? vec3(0.0) : heat(uMaxCount > 1.0 ? float(n - 1u) / (uMaxCount - 1.0) : 1.0);
  outColor = vec4(c * uInvExposure, 1.0);
}
