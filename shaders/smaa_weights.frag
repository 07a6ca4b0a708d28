#version 450 core
// SMAA, pass 2 of 3 (render/passes/smaa_passes.h): blending weights from
// the edge lines' shapes (orthogonal patterns, as SMAA 1x without its
// diagonal and corner modules). For the edge on the pixel's top side (and
// on its left side, the same turned), the line of edges is followed both
// ways up to uMaxSearch pixels, ending where the edge stops or a crossing
// edge meets it; a crossing edge at an end says the real outline passes
// through that crossing edge's middle (half a pixel into the row it is
// in). The outline is rebuilt as MLAA does (an L: from that half-pixel
// point to the far end; a Z or U: from each end to the line's middle) and
// its area inside this pixel's part of the line is integrated exactly.
// r: how much this pixel takes of the pixel above, g: how much the pixel
// above takes of this one; b, a: the same with the pixel to the left.
layout(binding = 0) uniform sampler2D uEdges;
uniform int uMaxSearch;
layout(location = 0) out vec4 outWeights;

ivec2 gSize;

vec2 edgeAt(ivec2 q) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, gSize))) return vec2(0.0);
  return texelFetch(uEdges, q, 0).rg;
}

// Height of the crossing edge at a line's end: -0.5 on this pixel's side,
// +0.5 on the other, 0 with none or both.
float endHeight(bool mine, bool other) { return mine == other ? 0.0 : (mine ? -0.5 : 0.5); }

// Areas of h over [a, b] where h is linear from (x0, h0) to (x1, h1):
// (below 0, above 0), as positive numbers.
vec2 segmentArea(float x0, float h0, float x1, float h1, float a, float b) {
  const float u = max(a, x0), v = min(b, x1);
  if (v <= u || x1 <= x0) return vec2(0.0);
  const float hu = mix(h0, h1, (u - x0) / (x1 - x0)), hv = mix(h0, h1, (v - x0) / (x1 - x0));
  if (hu * hv >= 0.0) {
    const float area = 0.5 * (hu + hv) * (v - u);
    return area < 0.0 ? vec2(-area, 0.0) : vec2(0.0, area);
  }
  const float z = u + (v - u) * hu / (hu - hv);
  const float first = 0.5 * hu * (z - u), second = 0.5 * hv * (v - z);
  return vec2(max(-first, 0.0) + max(-second, 0.0), max(first, 0.0) + max(second, 0.0));
}

// The outline of a line from boundary s to boundary t (t - s pixels long)
// with end heights h1 (at s) and h2 (at t), over this pixel's [x, x + 1].
vec2 lineArea(float s, float t, float h1, float h2, float x) {
  if (h1 == 0.0 && h2 == 0.0) return vec2(0.0);
  if (h1 != 0.0 && h2 != 0.0) {
    const float m = 0.5 * (s + t);
    return segmentArea(s, h1, m, 0.0, x, x + 1.0) + segmentArea(m, 0.0, t, h2, x, x + 1.0);
  }
  return segmentArea(s, h1, t, h2, x, x + 1.0);
}

void main() {
  gSize = textureSize(uEdges, 0);
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec2 e = edgeAt(p);
  vec4 w = vec4(0.0);
  if (e.g > 0.5) {
    // The line between rows y and y + 1; crossing edges at the boundary
    // between columns c - 1 and c are the left edges of (c, y) (this row)
    // and (c, y + 1) (the row above).
    int left = 0, right = 0;
    while (left < uMaxSearch && edgeAt(p + ivec2(-left - 1, 0)).g > 0.5 && edgeAt(p + ivec2(-left, 0)).r < 0.5 &&
           edgeAt(p + ivec2(-left, 1)).r < 0.5)
      ++left;
    while (right < uMaxSearch && edgeAt(p + ivec2(right + 1, 0)).g > 0.5 && edgeAt(p + ivec2(right + 1, 0)).r < 0.5 &&
           edgeAt(p + ivec2(right + 1, 1)).r < 0.5)
      ++right;
    const ivec2 s = p + ivec2(-left, 0), t = p + ivec2(right + 1, 0);
    const float h1 = endHeight(edgeAt(s).r > 0.5, edgeAt(s + ivec2(0, 1)).r > 0.5);
    const float h2 = endHeight(edgeAt(t).r > 0.5, edgeAt(t + ivec2(0, 1)).r > 0.5);
    w.rg = lineArea(float(s.x), float(t.x), h1, h2, float(p.x));
  }
  if (e.r > 0.5) {
    // The line between columns x - 1 and x; crossing edges at the boundary
    // between rows b - 1 and b are the top edges of (x, b - 1) (this
    // column) and (x - 1, b - 1) (the column to the left).
    int down = 0, up = 0;
    while (down < uMaxSearch && edgeAt(p + ivec2(0, -down - 1)).r > 0.5 && edgeAt(p + ivec2(0, -down - 1)).g < 0.5 &&
           edgeAt(p + ivec2(-1, -down - 1)).g < 0.5)
      ++down;
    while (up < uMaxSearch && edgeAt(p + ivec2(0, up + 1)).r > 0.5 && edgeAt(p + ivec2(0, up)).g < 0.5 &&
           edgeAt(p + ivec2(-1, up)).g < 0.5)
      ++up;
    const ivec2 s = p + ivec2(0, -down), t = p + ivec2(0, up + 1);
    const float h1 = endHeight(edgeAt(s + ivec2(0, -1)).g > 0.5, edgeAt(s + ivec2(-1, -1)).g > 0.5);
    const float h2 = endHeight(edgeAt(t + ivec2(0, -1)).g > 0.5, edgeAt(t + ivec2(-1, -1)).g > 0.5);
    w.ba = lineArea(float(s.y), float(t.y), h1, h2, float(p.y));
  }
  outWeights = w;
}
