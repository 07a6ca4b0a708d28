// Reading the A-buffer (abuffer.glsl) one pixel at a time into a local
// array, for a reader that needs the fragments together (the layered depth
// of field). The capture sorted each pixel's range (abuffer_sort_keys.comp):
// [abufferStarts[i], abufferStarts[i + 1]) is front to back, and nodes no
// fragment wrote (abufferWritten: a pixel of the fixed array with fewer
// fragments than layers, or a key tie) are skipped. A reader that takes
// one node at a time walks the range itself (oit_resolve.glsl).
// Use it from a compute shader, one invocation per pixel: in a fragment
// shader on llvmpipe a dynamically indexed local array read back zero for
// some pixels of a 4x4 block whose pixels had lists of different lengths.
// Define ABUFFER_MAX_FRAGMENTS before the include for another array length
// (64 by default).
//
// The order is the key's (oit_kbuffer.glsl's oitKey, in node.w): nearer
// first, ties in the depth's top 24 bits by a hash of object and primitive,
// the same order as the K-buffer's, so the two agree bit for bit.
#ifndef HS_ABUFFER_READ_GLSL
#define HS_ABUFFER_READ_GLSL
#include "abuffer.glsl"

#ifndef ABUFFER_MAX_FRAGMENTS
#define ABUFFER_MAX_FRAGMENTS 64
#endif

uvec4 abufferFragments[ABUFFER_MAX_FRAGMENTS];  // the loaded nodes, front to back

// The pixel's nearest written nodes (up to ABUFFER_MAX_FRAGMENTS) into
// abufferFragments, front to back; returns how many. `total` is the
// pixel's range length (what a caller that stops at the array's end left).
uint abufferLoadSorted(ivec2 pixel, out uint total) {
  const uint i = abufferPixel(pixel), begin = abufferStarts[i], end = abufferStarts[i + 1u];
  total = end - begin;
  uint n = 0u;
  for (uint k = begin; k < end && n < uint(ABUFFER_MAX_FRAGMENTS); ++k) {
    const uvec4 f = abufferNodes[k];
    if (abufferWritten(f)) abufferFragments[n++] = f;
  }
  return n;
}

#endif
