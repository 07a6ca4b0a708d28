#version 450 core
// SMAA, pass 3 of 3 (render/passes/smaa_passes.h): each pixel mixes in
// its neighbours by the weights of the lines on its sides (its own top and
// left, the top of the pixel below and the left of the pixel to the
// right), in display values as the picture holds them. As in SMAA, only the
// stronger direction's pair: a shallow line's one-pixel vertical steps
// would otherwise blend its pixels a second time, sideways.
layout(binding = 0) uniform sampler2D uImage;
layout(binding = 1) uniform sampler2D uWeights;
layout(location = 0) out vec4 outColor;

vec4 colourAt(ivec2 q) { return texelFetch(uImage, clamp(q, ivec2(0), textureSize(uImage, 0) - 1), 0); }

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const ivec2 size = textureSize(uWeights, 0);
  const vec4 own = texelFetch(uWeights, p, 0);
  // b = 1 marks a pixel on a diagonal run (smaa_weights.frag): it blends
  // vertically only, and the pixel right of it not across to it.
  const bool diagonal = own.b > 0.75;
  float top = own.r, left = diagonal ? 0.0 : own.b;
  float bottom = p.y > 0 ? texelFetch(uWeights, p + ivec2(0, -1), 0).g : 0.0;
  float right = !diagonal && p.x + 1 < size.x ? texelFetch(uWeights, p + ivec2(1, 0), 0).a : 0.0;
  if (p.x > 0 && texelFetch(uWeights, p + ivec2(-1, 0), 0).b > 0.75) left = 0.0;
  if (max(left, right) > max(top, bottom)) {
    top = 0.0;
    bottom = 0.0;
  } else {
    left = 0.0;
    right = 0.0;
  }
  const float sum = top + bottom + left + right;
  const vec4 c = colourAt(p);
  if (sum <= 0.0) {
    outColor = c;
    return;
  }
  const float k = sum > 1.0 ? 1.0 / sum : 1.0;
  outColor = c * (1.0 - sum * k) + k * (top * colourAt(p + ivec2(0, 1)) + bottom * colourAt(p + ivec2(0, -1)) +
                                        left * colourAt(p + ivec2(-1, 0)) + right * colourAt(p + ivec2(1, 0)));
}
