// One pixel's A-buffer list (abuffer.glsl) loaded into a local array and
// sorted front to back: for the transparency resolve (oit_resolve.comp) and
// the layered depth of field. Use it from a compute shader, one invocation
// per pixel: in a fragment shader on llvmpipe the array read back zero for
// some pixels of a 4x4 block whose pixels had lists of different lengths. Define ABUFFER_MAX_FRAGMENTS before the
// include for another array length (64 by default).
//
// Sorting is chosen by length: insertion sort up to ABUFFER_INSERTION_MAX
// fragments (few moves, no scratch), a bottom-up merge sort above (n log n).
// A list longer than the array keeps its ABUFFER_MAX_FRAGMENTS nearest
// fragments: the array is sorted when it fills, and each later fragment is
// inserted in order while the farthest falls off the end. A caller that
// wants every fragment continues with abufferLoadSortedAfter from the last
// one it has (oit_resolve.frag composites a long list in batches).
//
// The order is total over a fragment's content: nearer first (larger
// reversed-Z depth), then by colour bits. Two fragments that differ have
// the same order whatever order the list holds them in (which the atomics
// decide), so the resolve is deterministic; equal fragments are
// interchangeable.
#ifndef HS_ABUFFER_SORT_GLSL
#define HS_ABUFFER_SORT_GLSL
#include "abuffer.glsl"

#ifndef ABUFFER_MAX_FRAGMENTS
#define ABUFFER_MAX_FRAGMENTS 64
#endif
#define ABUFFER_INSERTION_MAX 16

uvec4 abufferFragments[ABUFFER_MAX_FRAGMENTS];  // the loaded fragments (nodes), front to back
uvec4 abufferScratch[ABUFFER_MAX_FRAGMENTS];

bool abufferBefore(uvec4 a, uvec4 b) {
  if (a.z != b.z) return a.z > b.z;  // depth bits: larger is nearer
  if (a.x != b.x) return a.x < b.x;
  return a.y < b.y;
}

bool abufferSame(uvec4 a, uvec4 b) { return a.xyz == b.xyz; }

void abufferInsertionSort(uint n) {
  for (uint i = 1u; i < n; ++i) {
    const uvec4 f = abufferFragments[i];
    uint j = i;
    while (j > 0u && abufferBefore(f, abufferFragments[j - 1u])) {
      abufferFragments[j] = abufferFragments[j - 1u];
      --j;
    }
    abufferFragments[j] = f;
  }
}

void abufferMergeSort(uint n) {
  for (uint width = 1u; width < n; width *= 2u) {
    for (uint lo = 0u; lo < n; lo += 2u * width) {
      const uint mid = min(lo + width, n), hi = min(lo + 2u * width, n);
      uint i = lo, j = mid, k = lo;
      while (i < mid && j < hi)
        abufferScratch[k++] = abufferBefore(abufferFragments[j], abufferFragments[i]) ? abufferFragments[j++]
                                                                                      : abufferFragments[i++];
      while (i < mid) abufferScratch[k++] = abufferFragments[i++];
      while (j < hi) abufferScratch[k++] = abufferFragments[j++];
    }
    for (uint k = 0u; k < n; ++k) abufferFragments[k] = abufferScratch[k];
  }
}

void abufferSort(uint n) {
  if (n <= uint(ABUFFER_INSERTION_MAX)) abufferInsertionSort(n);
  else abufferMergeSort(n);
}

// The array is full and sorted: keeps `f` if it is nearer than the last.
void abufferInsertBounded(uvec4 f) {
  uint j = uint(ABUFFER_MAX_FRAGMENTS) - 1u;
  if (!abufferBefore(f, abufferFragments[j])) return;
  while (j > 0u && abufferBefore(f, abufferFragments[j - 1u])) {
    abufferFragments[j] = abufferFragments[j - 1u];
    --j;
  }
  abufferFragments[j] = f;
}

// Loads into abufferFragments, front to back, the nearest (up to
// ABUFFER_MAX_FRAGMENTS) of the pixel's fragments that come after `after`
// (all of them when `hasAfter` is false); `loaded` is how many. Returns how
// many fragments come after `after` in all (more than `loaded`: call again
// from the last one loaded) and counts in `sameAsAfter` the fragments equal
// to `after` (copies a caller may not have had room for).
uint abufferLoadSortedAfter(ivec2 pixel, bool hasAfter, uvec4 after, out uint loaded, out uint sameAsAfter) {
  uint n = 0u, matching = 0u;
  sameAsAfter = 0u;
  uint node = abufferHeads[abufferPixel(pixel)];
  while (node != ABUFFER_END) {
    const uvec4 f = abufferNodes[node];
    node = f.w;
    if (hasAfter) {
      if (abufferSame(f, after)) {
        ++sameAsAfter;
        continue;
      }
      if (!abufferBefore(after, f)) continue;
    }
    ++matching;
    if (n < uint(ABUFFER_MAX_FRAGMENTS)) {
      abufferFragments[n++] = f;
      if (n == uint(ABUFFER_MAX_FRAGMENTS)) abufferSort(n);
    } else {
      abufferInsertBounded(f);
    }
  }
  if (n < uint(ABUFFER_MAX_FRAGMENTS)) abufferSort(n);
  loaded = n;
  return matching;
}

// The pixel's nearest fragments, front to back (how many were loaded);
// `total` is the list's length.
uint abufferLoadSorted(ivec2 pixel, out uint total) {
  uint loaded, same;
  total = abufferLoadSortedAfter(pixel, false, uvec4(0u), loaded, same);
  return loaded;
}

#endif
