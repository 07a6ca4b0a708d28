#version 450 core
// Depth of field: the largest CoC radius (pixels) in each 16 x 16 tile of
// the depth, so a gather samples a disc no wider than the blur around it
// (a frame-wide radius spreads the taps thin where the blur is small).
layout(binding = 25) uniform sampler2D uDepth;
layout(location = 0) out vec4 outMax;

#include "dof_common.glsl"

void main() {
  ivec2 size = textureSize(uDepth, 0);
  ivec2 base = ivec2(gl_FragCoord.xy) * 16;
  float m = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      ivec2 q = min(base + ivec2(x, y), size - 1);
      m = max(m, abs(dofCocRadius(texelFetch(uDepth, q, 0).r)));
    }
  outMax = vec4(m);
}
