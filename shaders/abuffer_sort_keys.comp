#version 450 core
// The A-buffer's sort (abuffer.glsl): each pixel's (depth, key) pairs in
// order, nearest first (abufferNearer), in place in the node pool, one
// invocation per pixel. Insertion sort for short ranges (few moves, linear
// on the nearly sorted), heapsort above ABUFFER_INSERTION_MAX (n log n with
// no scratch: a range can be thousands of nodes). A pixel over its cap
// needs none: the key pass's atomicMin chain left its keys in order.
layout(local_size_x = 8, local_size_y = 8) in;
#include "abuffer.glsl"
uniform ivec2 uSize;
#define ABUFFER_INSERTION_MAX 16u

uint base;  // the pixel's first node

// A node's (depth bits, key): what the range is sorted by (abufferNearer).
uvec2 at(uint i) { return abufferNodes[base + i].zw; }
void put(uint i, uvec2 k) { abufferNodes[base + i].zw = k; }

void siftDown(uint root, uint n) {  // a max-heap on "farther"
  const uvec2 k = at(root);
  uint i = root;
  for (;;) {
    uint child = 2u * i + 1u;
    if (child >= n) break;
    if (child + 1u < n && abufferNearer(at(child), at(child + 1u))) ++child;
    const uvec2 c = at(child);
    if (!abufferNearer(k, c)) break;
    put(i, c);
    i = child;
  }
  put(i, k);
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= uSize.x || p.y >= uSize.y) return;
  const uint pixel = abufferPixel(p);
  base = abufferStarts[pixel];
  const uint range = abufferStarts[pixel + 1u] - base;
  if (abufferByKey(p, range)) return;
  // The nodes the key pass wrote; the rest of a fixed array's range stays empty.
  const uint n = imageLoad(uABufferCounts, p).x;
  if (n < 2u) return;
  if (n <= ABUFFER_INSERTION_MAX) {
    for (uint i = 1u; i < n; ++i) {
      const uvec2 k = at(i);
      uint j = i;
      while (j > 0u && abufferNearer(k, at(j - 1u))) {
        put(j, at(j - 1u));
        --j;
      }
      put(j, k);
    }
    return;
  }
  for (uint i = n / 2u; i > 0u; --i) siftDown(i - 1u, n);
  for (uint end = n - 1u; end > 0u; --end) {
    const uvec2 top = at(0u);
    put(0u, at(end));
    put(end, top);
    siftDown(0u, end);
  }
}
