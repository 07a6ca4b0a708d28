#version 450 core
// The A-buffer's sort (abuffer.glsl): each pixel's keys in order, nearest
// first, in place in the node pool, one invocation per pixel. Insertion
// sort for short ranges (few moves, linear on the nearly sorted), heapsort
// above ABUFFER_INSERTION_MAX (n log n with no scratch: a range can be
// thousands of nodes). A pixel over its cap needs none: the key pass's
// atomicMin chain left its keys in order.
layout(local_size_x = 8, local_size_y = 8) in;
#include "abuffer.glsl"
uniform ivec2 uSize;
#define ABUFFER_INSERTION_MAX 16u

uint base;  // the pixel's first node

uint keyAt(uint i) { return abufferNodes[base + i].w; }
void setKey(uint i, uint k) { abufferNodes[base + i].w = k; }

void siftDown(uint root, uint n) {
  const uint k = keyAt(root);
  uint i = root;
  for (;;) {
    uint child = 2u * i + 1u;
    if (child >= n) break;
    if (child + 1u < n && keyAt(child + 1u) > keyAt(child)) ++child;
    const uint c = keyAt(child);
    if (c <= k) break;
    setKey(i, c);
    i = child;
  }
  setKey(i, k);
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= uSize.x || p.y >= uSize.y) return;
  const uint pixel = abufferPixel(p);
  base = abufferStarts[pixel];
  const uint range = abufferStarts[pixel + 1u] - base, count = imageLoad(uABufferCounts, p).x;
  if (count > range) return;
  const uint n = count;  // the keys the key pass wrote; the rest of a fixed array's range stays empty
  if (n < 2u) return;
  if (n <= ABUFFER_INSERTION_MAX) {
    for (uint i = 1u; i < n; ++i) {
      const uint k = keyAt(i);
      uint j = i;
      while (j > 0u && keyAt(j - 1u) > k) {
        setKey(j, keyAt(j - 1u));
        --j;
      }
      setKey(j, k);
    }
    return;
  }
  for (uint i = n / 2u; i > 0u; --i) siftDown(i - 1u, n);
  for (uint end = n - 1u; end > 0u; --end) {
    const uint top = keyAt(0u);
    setKey(0u, keyAt(end));
    setKey(end, top);
    siftDown(0u, end);
  }
}
