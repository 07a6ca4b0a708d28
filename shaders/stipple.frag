#version 450 core
// Weighted Voronoi stippling's dots (render/passes/stipple_passes.h): black
// discs of radius uRadius on white paper, one per site, anti-aliased over a
// pixel. A pixel finds the sites that can reach it in the owner map around
// it (every site owns the cell it stands in); overlapping dots take the
// darker (a max: no order).
layout(binding = 0) uniform sampler2D uSites;  // RG32F per grid cell: its site, in cells ((-1, -1): none)
uniform vec2 uScale;   // pixels per grid cell
uniform float uRadius; // pixels
uniform int uReach;    // cells searched each way
layout(location = 0) out vec4 outColor;

void main() {
  const ivec2 size = textureSize(uSites, 0);
  const vec2 p = gl_FragCoord.xy;
  const ivec2 c = ivec2(p / uScale);
  float ink = 0.0;
  for (int dy = -uReach; dy <= uReach; ++dy)
    for (int dx = -uReach; dx <= uReach; ++dx) {
      const ivec2 n = c + ivec2(dx, dy);
      if (n.x < 0 || n.y < 0 || n.x >= size.x || n.y >= size.y) continue;
      const vec2 s = texelFetch(uSites, n, 0).xy;
      if (s.x < 0.0) continue;
      ink = max(ink, clamp(uRadius + 0.5 - distance(p, s * uScale), 0.0, 1.0));
    }
  outColor = vec4(vec3(1.0 - ink), 1.0);
}
