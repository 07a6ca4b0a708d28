#version 450 core
// Applies ambient occlusion to the ambient term only: the scene colour's
// alpha holds the ambient light's share of its luminance (lighting.glsl,
// hsAmbientShare), so the colour loses (1 - ao) of that share. The AO is
// blurred over 4 x 4 of its texels (half or full resolution), weighting
// out texels whose depth differs, so the noise of ssao.frag goes and edges
// stay.
in vec2 vUv;
layout(binding = 0) uniform sampler2D uScene;
layout(binding = 1) uniform sampler2D uAo;
layout(binding = 2) uniform sampler2D uDepth;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 c = texture(uScene, vUv);
  float depth = texture(uDepth, vUv).r;
  if (depth <= 0.0) {
    outColor = c;
    return;
  }
  vec2 texel = 1.0 / vec2(textureSize(uAo, 0));
  float sum = 0.0, weight = 0.0;
  for (int y = -2; y < 2; ++y)
    for (int x = -2; x < 2; ++x) {
      vec2 uv = vUv + (vec2(x, y) + 0.5) * texel;
      float d = texture(uDepth, uv).r;
      // Reversed-Z depth is 1/distance-like: compare relatively.
      float w = exp(-abs(d - depth) / (0.02 * depth));
      sum += texture(uAo, uv).r * w;
      weight += w;
    }
  float ao = weight > 0.0 ? sum / weight : 1.0;
  outColor = vec4(c.rgb * (1.0 - (1.0 - ao) * clamp(c.a, 0.0, 1.0)), c.a);
}
