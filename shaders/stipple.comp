#version 450 core
// Weighted Voronoi stippling's relaxation (Secord 2002; render/passes/
// stipple_passes.h), one stage per define, on the half-resolution grid:
//   HS_STIPPLE_SEED    per candidate i: at the Halton point (base 2, 3) i+1,
//                      kept if the darkness there, 0..255, beats an integer
//                      hash of i modulo 255 (kept with probability
//                      darkness / 255: dots per area as the image is dark,
//                      every one where it is black); into slot uFirst + i
//   HS_STIPPLE_REPROJECT (the second eye of a stereo pair) per first-eye
//                      dot i: through its depth to this eye's grid, kept
//                      where this eye sees that surface (not occluded, in
//                      frame); into slot i
//   HS_STIPPLE_FILL    per own candidate (slot uFirst + i) of the second
//                      eye: dropped where the flood of the reprojected
//                      dots finds one nearer than the spacing the
//                      darkness there asks for (only holes are filled)
//   HS_STIPPLE_SPLAT   per site: its index into the owner map (atomicMin:
//                      the lower index wins a shared cell)
//   HS_STIPPLE_MERGE   per cell: the nearer of its seed and its owner in the
//                      previous step's cells (OwnerOut holds those), the
//                      start of a short flood after the first step
//   HS_STIPPLE_JUMP    per cell: jump flooding, the nearest of the sites its
//                      8 neighbours at uStep know (ties: the lower index)
//   HS_STIPPLE_SUM     per cell: darkness and darkness-weighted position
//                      added into its owner's sums (integers: exact, so the
//                      order of the atomics does not matter)
//   HS_STIPPLE_MOVE    per site from uFirst on: to the centroid of its cell
//                      (the slots before, reprojected dots, stay)
//   HS_STIPPLE_RESOLVE per cell: its owner's position into the map the
//                      dots are drawn from ((-1, -1): none)
// Positions are in grid cells, a cell's centre at (x + 0.5, y + 0.5).
#if defined(HS_STIPPLE_JUMP) || defined(HS_STIPPLE_MERGE) || defined(HS_STIPPLE_SUM) || defined(HS_STIPPLE_RESOLVE)
layout(local_size_x = 8, local_size_y = 8) in;
#else
layout(local_size_x = 64) in;
#endif
layout(binding = 0) uniform sampler2D uDensity;  // R8: darkness per cell
layout(std430, binding = 0) buffer Sites { vec2 site[]; };  // x < 0: no dot in this slot
layout(std430, binding = 1) buffer OwnerIn { uint ownerIn[]; };
layout(std430, binding = 2) buffer OwnerOut { uint ownerOut[]; };
// Per site 5 words: sum of w, then sum of w (2x + 1) and of w (2y + 1) as
// 64-bit numbers (low, high): w is 0..255, 2x + 1 under 2^14, a cell of a
// million pixels fits.
layout(std430, binding = 3) buffer Sums { uint sums[]; };
layout(std430, binding = 4) buffer FirstSites { vec2 firstSite[]; };  // REPROJECT: the first eye's
layout(binding = 1) uniform sampler2D uFirstDepth;  // REPROJECT: single-sample, reversed-Z
layout(binding = 2) uniform sampler2D uDepth;
layout(binding = 0, rg32f) uniform writeonly image2D uMap;
uniform ivec2 uSize;   // the grid
uniform uint uCount;   // the slots a per-slot stage runs over
uniform uint uFirst;   // SEED, FILL: where its slots start; MOVE: the first that moves
uniform mat4 uFirstToThis;    // REPROJECT: first eye's NDC (z: depth) to this eye's clip space
uniform vec2 uPixelsPerCell;  // REPROJECT: pixels per grid cell each way
uniform float uSpacing;       // FILL: the dots' spacing where black, cells
uniform int uStep;     // jump flooding's step, cells

const uint kNone = 0xffffffffu;

#include "lowbias32.glsl"

uint darknessAt(ivec2 c) { return uint(texelFetch(uDensity, c, 0).r * 255.0 + 0.5); }

// The radical inverse of i in `base` (Halton's sequence).
float radicalInverse(uint i, uint base) {
  float inv = 1.0 / float(base), f = inv, r = 0.0;
  while (i > 0u) {
    r += f * float(i % base);
    i /= base;
    f *= inv;
  }
  return r;
}

void add64(uint at, uint v) {
  const uint old = atomicAdd(sums[at], v);
  if (old + v < old) atomicAdd(sums[at + 1u], 1u);  // the low word wrapped: carry
}

float distance2(uint s, vec2 p) {
  const vec2 d = site[s] - p;
  return dot(d, d);
}

void main() {
#if defined(HS_STIPPLE_SEED) || defined(HS_STIPPLE_SPLAT) || defined(HS_STIPPLE_MOVE) || \
    defined(HS_STIPPLE_REPROJECT) || defined(HS_STIPPLE_FILL)
  const uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
#if defined(HS_STIPPLE_SEED)
  const vec2 p = vec2(radicalInverse(i + 1u, 2u), radicalInverse(i + 1u, 3u)) * vec2(uSize);
  const ivec2 c = min(ivec2(p), uSize - 1);
  site[uFirst + i] = darknessAt(c) > lowbias32(i) % 255u ? p : vec2(-1.0);
#elif defined(HS_STIPPLE_REPROJECT)
  const vec2 p = firstSite[i];
  site[i] = vec2(-1.0);
  if (p.x < 0.0) return;
  const ivec2 pixels = textureSize(uDepth, 0);
  const ivec2 at = clamp(ivec2(p * uPixelsPerCell), ivec2(0), pixels - 1);
  // Depth 0 is the far plane (the sky): still a point, far away.
  const float depth = max(texelFetch(uFirstDepth, at, 0).r, 1e-9);
  const vec4 clip = uFirstToThis * vec4(p / vec2(uSize) * 2.0 - 1.0, depth, 1.0);
  if (clip.w <= 0.0) return;
  const vec3 ndc = clip.xyz / clip.w;
  const vec2 q = (ndc.xy * 0.5 + 0.5) * vec2(uSize);
  if (q.x < 0.0 || q.y < 0.0 || q.x >= float(uSize.x) || q.y >= float(uSize.y)) return;
  // Occluded here: this eye sees something nearer there (reversed-Z: a
  // larger depth), by more than 2 % of the distance.
  const float seen = texelFetch(uDepth, min(ivec2(q * uPixelsPerCell), pixels - 1), 0).r;
  if (seen > ndc.z * 1.02 + 1e-9) return;
  site[i] = q;
#elif defined(HS_STIPPLE_FILL)
  const uint slot = uFirst + i;
  const vec2 p = site[slot];
  if (p.x < 0.0) return;
  const ivec2 c = clamp(ivec2(p), ivec2(0), uSize - 1);
  const uint owner = ownerIn[uint(c.y) * uint(uSize.x) + uint(c.x)];
  // Accepted with probability darkness / 255, dots are about
  // spacing / sqrt(darkness) apart: a reprojected one nearer than most of
  // that covers this place.
  const float darkness = max(float(darknessAt(c)), 1.0) / 255.0;
  if (owner != kNone && distance(site[owner], p) < 0.85 * uSpacing * inversesqrt(darkness)) site[slot] = vec2(-1.0);
#elif defined(HS_STIPPLE_SPLAT)
  const vec2 p = site[i];
  if (p.x < 0.0) return;
  const ivec2 c = clamp(ivec2(p), ivec2(0), uSize - 1);
  atomicMin(ownerIn[uint(c.y) * uint(uSize.x) + uint(c.x)], i);
#else
  if (i < uFirst || site[i].x < 0.0) return;
  const uint w = sums[i * 5u];
  if (w == 0u) return;  // a cell with no darkness (or none at all) keeps its site
  const float sx = float(sums[i * 5u + 2u]) * 4294967296.0 + float(sums[i * 5u + 1u]);
  const float sy = float(sums[i * 5u + 4u]) * 4294967296.0 + float(sums[i * 5u + 3u]);
  site[i] = vec2(sx, sy) / (2.0 * float(w));
#endif
#else
  const ivec2 c = ivec2(gl_GlobalInvocationID.xy);
  if (c.x >= uSize.x || c.y >= uSize.y) return;
  const uint at = uint(c.y) * uint(uSize.x) + uint(c.x);
#if defined(HS_STIPPLE_JUMP)
  const vec2 centre = vec2(c) + 0.5;
  uint best = ownerIn[at];
  float bestD = best == kNone ? 3.4e38 : distance2(best, centre);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const ivec2 n = c + ivec2(dx, dy) * uStep;
      if ((dx == 0 && dy == 0) || n.x < 0 || n.y < 0 || n.x >= uSize.x || n.y >= uSize.y) continue;
      const uint s = ownerIn[uint(n.y) * uint(uSize.x) + uint(n.x)];
      if (s == kNone || s == best) continue;
      const float d = distance2(s, centre);
      if (d < bestD || (d == bestD && s < best)) {
        best = s;
        bestD = d;
      }
    }
  ownerOut[at] = best;
#elif defined(HS_STIPPLE_MERGE)
  const vec2 centre = vec2(c) + 0.5;
  const uint seed = ownerIn[at], before = ownerOut[at];
  uint best = seed;
  if (before != kNone && before != seed &&
      (seed == kNone || distance2(before, centre) < distance2(seed, centre) ||
       (distance2(before, centre) == distance2(seed, centre) && before < seed)))
    best = before;
  ownerOut[at] = best;
#elif defined(HS_STIPPLE_SUM)
  const uint s = ownerIn[at];
  const uint w = darknessAt(c);
  if (s == kNone || w == 0u) return;
  atomicAdd(sums[s * 5u], w);
  add64(s * 5u + 1u, w * uint(2 * c.x + 1));
  add64(s * 5u + 3u, w * uint(2 * c.y + 1));
#else
  const uint s = ownerIn[at];
  imageStore(uMap, c, s == kNone ? vec4(-1.0) : vec4(site[s], 0.0, 0.0));
#endif
#endif
}
