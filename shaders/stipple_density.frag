#version 450 core
// Weighted Voronoi stippling's density (render/passes/stipple_passes.h):
// the darkness (1 - Rec. 709 luma of the display-encoded image) of each
// cell of the half-resolution grid, the mean over the 2 x 2 pixels it covers
// (those inside the image at an odd size).
layout(binding = 0) uniform sampler2D uImage;
layout(location = 0) out vec4 outDarkness;

void main() {
  const ivec2 size = textureSize(uImage, 0);
  const ivec2 base = ivec2(gl_FragCoord.xy) * 2;
  float sum = 0.0;
  int n = 0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const ivec2 p = base + ivec2(x, y);
      if (p.x >= size.x || p.y >= size.y) continue;
      sum += dot(texelFetch(uImage, p, 0).rgb, vec3(0.2126, 0.7152, 0.0722));
      ++n;
    }
  outDarkness = vec4(clamp(1.0 - sum / float(max(n, 1)), 0.0, 1.0));
}
