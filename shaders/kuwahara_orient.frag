#version 450 core
// Anisotropic Kuwahara, step 2 of 3: the structure tensor smoothed (a
// Gaussian, sigma 1.5 px, over 7 x 7 pixels), then its eigenvectors: the
// direction along the structure (the minor one) and the anisotropy
// A = (l1 - l2) / (l1 + l2) in 0..1 (0 where the image is flat or
// isotropic; there the direction is arbitrary and the ellipse a circle).
layout(binding = 0) uniform sampler2D uTensor;
layout(location = 0) out vec4 outColor;

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const ivec2 last = textureSize(uTensor, 0) - 1;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int j = -3; j <= 3; ++j)
    for (int i = -3; i <= 3; ++i) {
      const float w = exp(-float(i * i + j * j) / (2.0 * 1.5 * 1.5));
      sum += w * texelFetch(uTensor, clamp(p + ivec2(i, j), ivec2(0), last), 0).rgb;
      weights += w;
    }
  const vec3 s = sum / weights;  // E, G, F
  const float e = s.x, g = s.y, f = s.z;
  const float root = sqrt((e - g) * (e - g) + 4.0 * f * f);
  const float l1 = 0.5 * (e + g + root), l2 = 0.5 * (e + g - root);
  vec2 t = vec2(l1 - e, -f);
  t = dot(t, t) > 1e-12 ? normalize(t) : vec2(0.0, 1.0);
  const float a = l1 + l2 > 1e-8 ? (l1 - l2) / (l1 + l2) : 0.0;
  outColor = vec4(t, a, 1.0);
}
