#version 450 core
// SMAA, pass 2 of 3 (render/passes/smaa_passes.h): blending weights from
// the edge lines' shapes (SMAA 1x's orthogonal and diagonal patterns and
// its corner detection). A pixel on a diagonal run takes its weights
// from that (diagonalOffset below); otherwise, for the edge on the pixel's
// top side (and on its left side, the same turned), the line of edges is followed both
// ways up to uMaxSearch pixels, ending where the edge stops or a crossing
// edge meets it; a crossing edge at an end says the real outline passes
// through that crossing edge's middle (half a pixel into the row it is
// in). The outline is rebuilt as MLAA does (an L: from that half-pixel
// point to the far end; a Z or U: from each end to the line's middle) and
// its area inside this pixel's part of the line is integrated exactly.
// r: how much this pixel takes of the pixel above, g: how much the pixel
// above takes of this one; b, a: the same with the pixel to the left (b =
// 1: the pixel is on a diagonal run, a is 0). The pass runs at edge pixels
// only (smaa_passes.cpp's depth mask). The diagonal search is in the
// shader once: llvmpipe runs the code of an if for every pixel of a block,
// taken or not, so each copy costs every shaded pixel (the blend reads the
// mark instead of a second search from the neighbour).
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

// SMAA's corner module: where a line's end meets a crossing edge that
// goes on past the one-pixel step a staircase would make, the outline has
// a real corner there; the part of the line that end shapes (the nearer
// end of a Z or U, the known end of an L) keeps a quarter of its areas
// (SMAA's corner rounding, 25 %) instead of being rounded off.
const float kCornerKeep = 0.25;
float cornerFactor(bool corner1, bool corner2, float h1, float h2, float s, float t, float x) {
  bool corner = false;
  if (h1 != 0.0 && h2 != 0.0) corner = x + 0.5 < 0.5 * (s + t) ? corner1 : corner2;
  else if (h1 != 0.0) corner = corner1;
  else if (h2 != 0.0) corner = corner2;
  return corner ? kCornerKeep : 1.0;
}

// Diagonal patterns (SMAA's diagonal module, rebuilt the MLAA way in the
// frame turned 45°; the CPU twin's diagonalOffset says it at length): q on
// the lower side of a staircase of one-pixel steps, edges on its top and
// its left (or, `mirrored`, its right: a slope of -1), the run of such
// pixels followed along the diagonal both ways. A step at an end with the
// outline going on beyond it (another run, or a line the same way; not the
// picture's border) says how the line leaves the diagonal: horizontal
// (shallower than 45°; that step is a column of its own, the last of the
// run before it) or vertical (steeper). The outline's height over the
// staircase's midpoint line is +-0.5 there and goes linearly through 0 at
// the middle (one end known: to 0 at the other); both ends the same way
// (a bend) are left to the orthogonal patterns. `offset`: the height at
// q's corner triangle (a quarter column before its centre) and at the
// pixel above's (a quarter after).
const int kMinDiagonal = 3;
bool edgeLeft(ivec2 q) { return edgeAt(q).r > 0.5; }
bool edgeTop(ivec2 q) { return edgeAt(q).g > 0.5; }
bool topOf(ivec2 q, bool mirrored, int dx, int dy) { return edgeTop(q + ivec2(mirrored ? -dx : dx, dy)); }
bool leftOf(ivec2 q, bool mirrored, int dx, int dy) {
  return mirrored ? edgeLeft(q + ivec2(1 - dx, dy)) : edgeLeft(q + ivec2(dx, dy));
}
bool lowerSide(ivec2 q, bool mirrored, int dx, int dy) {
  return topOf(q, mirrored, dx, dy) && leftOf(q, mirrored, dx, dy) && !leftOf(q, mirrored, dx + 1, dy) &&
         !topOf(q, mirrored, dx, dy - 1);
}
bool diagonalOffset(ivec2 q, bool mirrored, out vec2 offset) {
  offset = vec2(0.0);
  if (!lowerSide(q, mirrored, 0, 0)) return false;
  int back = 0, ahead = 0;
  while (back < uMaxSearch && lowerSide(q, mirrored, -back - 1, -back - 1)) ++back;
  while (ahead < uMaxSearch && lowerSide(q, mirrored, ahead + 1, ahead + 1)) ++ahead;
  const int n = back + ahead + 1;
  if (n < kMinDiagonal) return false;
  const int a = -back, b = ahead;
  float h1 = 0.0, h2 = 0.0, start = 0.0;
  const float end = float(n);
  if (back < uMaxSearch) {
    if (topOf(q, mirrored, a - 1, a - 1) && !leftOf(q, mirrored, a - 1, a - 1) &&
        (lowerSide(q, mirrored, a - 2, a - 1) || topOf(q, mirrored, a - 2, a - 1))) {
      h1 = 0.5;
      start = -1.0;
    } else if (leftOf(q, mirrored, a, a - 1) && !topOf(q, mirrored, a, a - 1) &&
               (lowerSide(q, mirrored, a - 1, a - 2) || leftOf(q, mirrored, a, a - 2))) {
      h1 = -0.5;
    }
  }
  if (ahead < uMaxSearch) {
    if (topOf(q, mirrored, b + 1, b) && !leftOf(q, mirrored, b + 1, b) &&
        (lowerSide(q, mirrored, b + 2, b + 1) || topOf(q, mirrored, b + 2, b)))
      h2 = -0.5;
    else if (leftOf(q, mirrored, b + 1, b + 1) && !topOf(q, mirrored, b + 1, b + 1) &&
             (lowerSide(q, mirrored, b + 1, b + 2) || leftOf(q, mirrored, b + 1, b + 2)))
      h2 = 0.5;
  }
  // Both ends leaving the same way (a U: a curve's silhouette bending):
  // how far it bulges is not in the run; the orthogonal patterns do better.
  if (h1 != 0.0 && h1 == h2) return false;
  const float mid = 0.5 * (start + end);
  for (int i = 0; i < 2; ++i) {
    const float t = float(back) + (i == 0 ? 0.25 : 0.75);
    float h = 0.0;
    if (h1 != 0.0 && h2 != 0.0) h = t < mid ? h1 * (mid - t) / (mid - start) : h2 * (t - mid) / (end - mid);
    else if (h1 != 0.0) h = h1 * (end - t) / (end - start);
    else if (h2 != 0.0) h = h2 * (t - start) / (end - start);
    offset[i] = h;
  }
  return true;
}

void main() {
  gSize = textureSize(uEdges, 0);
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec2 e = edgeAt(p);
  vec4 w = vec4(0.0);
  vec2 offset;
  // On a diagonal run a pixel has its top edge, one side edge (left: slope
  // +1, right: -1) and none below: checked first, so the search (one, for
  // the side it has) runs only there.
  const bool rightEdge = edgeAt(p + ivec2(1, 0)).r > 0.5;
  bool diagonal = e.g > 0.5 && (e.r > 0.5) != rightEdge && edgeAt(p + ivec2(0, -1)).g < 0.5;
  if (diagonal) diagonal = diagonalOffset(p, rightEdge, offset);
  if (diagonal) {
    // The outline y = x + 0.5 + offset over this pixel (the lower side)
    // and the one above: their corner triangles. Only the vertical pair
    // blends; the side edge's weights stay 0.
    // b = 1 (never an area: those stay under 0.5) marks the pixel as on a
    // run for the blend, which then keeps it and its right-hand neighbour
    // from blending across the side edge.
    w = vec4(0.5 * (0.5 - offset.x) * (0.5 - offset.x), 0.5 * (0.5 + offset.y) * (0.5 + offset.y), 1.0, 0.0);
  }
  if (!diagonal && e.g > 0.5) {
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
    // Corners: the crossing edge going on below (this row's side) or above
    // (the other's).
    const bool c1 = h1 < 0.0 ? edgeAt(s + ivec2(0, -1)).r > 0.5 : (h1 > 0.0 && edgeAt(s + ivec2(0, 2)).r > 0.5);
    const bool c2 = h2 < 0.0 ? edgeAt(t + ivec2(0, -1)).r > 0.5 : (h2 > 0.0 && edgeAt(t + ivec2(0, 2)).r > 0.5);
    w.rg = lineArea(float(s.x), float(t.x), h1, h2, float(p.x)) *
           cornerFactor(c1, c2, h1, h2, float(s.x), float(t.x), float(p.x));
  }
  if (!diagonal && e.r > 0.5) {
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
    // Corners: the crossing edge going on right of this column (its side)
    // or left of the column before (the other's).
    const bool c1 = h1 < 0.0 ? edgeAt(s + ivec2(1, -1)).g > 0.5 : (h1 > 0.0 && edgeAt(s + ivec2(-2, -1)).g > 0.5);
    const bool c2 = h2 < 0.0 ? edgeAt(t + ivec2(1, -1)).g > 0.5 : (h2 > 0.0 && edgeAt(t + ivec2(-2, -1)).g > 0.5);
    w.ba = lineArea(float(s.y), float(t.y), h1, h2, float(p.y)) *
           cornerFactor(c1, c2, h1, h2, float(s.y), float(t.y), float(p.y));
  }
  outWeights = w;
}
