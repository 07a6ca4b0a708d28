// Depth of field (docs/rendering.md "Depth of field", render/dof_lens.h):
// the circle of confusion of a reversed-Z depth. Included by the dof_*
// shaders; their uniforms:
//   uCocScale    pixels of CoC diameter per unit of (1/s - 1/z), 1/m
//   uInvFocus    1/s, the focus distance's inverse
//   uDepthToInvZ (x, y): 1/z = (depth + x) / y for the view's projection
//   uMaxRadius   the largest CoC radius (pixels) the passes blur by
uniform float uCocScale;
uniform float uInvFocus;
uniform vec2 uDepthToInvZ;
uniform float uMaxRadius;

// Signed CoC radius in pixels (negative in front of the focus plane);
// depth 0 is the sky, at infinity.
float dofCocRadius(float depth) {
  float invZ = depth > 0.0 ? (depth + uDepthToInvZ.x) / uDepthToInvZ.y : 0.0;
  return clamp(0.5 * uCocScale * (uInvFocus - invZ), -uMaxRadius, uMaxRadius);
}

// How much of a pixel at distance `dist` a disc of radius `r` covers
// (smoothed over one pixel, so a radius under half a pixel covers only its
// own pixel).
float dofCover(float r, float dist) { return clamp(r - dist + 0.5, 0.0, 1.0); }

// Tap i of n on Vogel's sunflower in the disc of radius `radius` pixels.
vec2 dofTap(int i, int n, float radius) {
  float r = radius * sqrt((float(i) + 0.5) / float(n));
  float a = float(i) * 2.39996323;
  return r * vec2(cos(a), sin(a));
}

// The largest CoC radius that can reach pixel `p`: the tile maxima
// (dof_tiles.frag, 16 x 16 pixels) of its tile and the two around it each
// way (uMaxRadius is at most 32 pixels, two tiles).
float dofNeighbourhoodRadius(sampler2D tiles, ivec2 p) {
  ivec2 t = p / 16, n = textureSize(tiles, 0) - 1;
  float m = 0.0;
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x) m = max(m, texelFetch(tiles, clamp(t + ivec2(x, y), ivec2(0), n), 0).r);
  return m;
}
