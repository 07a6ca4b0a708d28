// The A-buffer: every fragment of a pixel in one contiguous, sorted range
// of a node pool (render/abuffer.h is the C++ side; the bindings and
// layouts must match). Per-pixel ranges come from a prefix sum of the
// counting pass's counts, as in the S-buffer (Vasilakis & Fudos 2012),
// instead of linked lists (Yang et al. 2010): see abuffer_keys.frag for why.
//   image unit 1  counts  r32ui: fragments per pixel (the counting pass; depth complexity)
//   buffer 15     starts  uint per pixel and one more (row-major, abufferPixel):
//                         pixel i's nodes are [starts[i], starts[i + 1]); for the
//                         fixed array (abuffer_fixed) every range has fixedLayers nodes
//   buffer 16     cursor  uint per pixel: the key pass's next free node of the pixel
//                         (the capture's alone; abuffer_scan.comp borrows it first)
//   buffer 12     nodes   uvec4 per fragment: x packHalf2x16(r, g), y packHalf2x16(b, a)
//                         (straight colour, linear HDR, and opacity; both ABUFFER_UNWRITTEN
//                         until the lit pass writes them), z depth bits, w key
//                         (oit_kbuffer.glsl's oitKey): a pixel's nodes are sorted nearest
//                         first by full depth, equal depths by key (abufferNearer); a pixel
//                         over its cap by key alone (the atomicMin chain's order)
//   buffer 13     ABufferCounters (below)
//   buffer 14     tail    (with a tail) 4 uints per pixel: what did not fit the pool
//                         (oit_tail.glsl), order-independent integer sums
// Depth is gl_FragCoord.z in the renderer's reversed Z (1 near, 0 far):
// non-negative floats, so their bits compare like the floats.
#ifndef HS_ABUFFER_GLSL
#define HS_ABUFFER_GLSL

#define ABUFFER_UNWRITTEN 0xFFFFFFFFu  // a node's colour words before the lit pass (half NaNs: no real colour)

layout(binding = 1, r32ui) uniform coherent uimage2D uABufferCounts;

layout(std430, binding = 12) coherent buffer ABufferNodes { uvec4 abufferNodes[]; };

// Filled by the counting pass (fragments, maxPerPixel, coveredPixels), the
// CPU (perPixelCap, capacity) and the lit pass (overflow); the tail and
// resolve add theirs.
layout(std430, binding = 13) coherent buffer ABufferCounters {
  uint perPixelCap;    // nodes a pixel may have (the CPU, from the memory cap; 0xFFFFFFFF: no cap)
  uint fragments;      // the counting pass: fragments in all
  uint maxPerPixel;    // the counting pass: the deepest pixel
  uint coveredPixels;  // the counting pass: pixels with at least one fragment
  uint capacity;       // nodes in the pool (set by the CPU before the capture)
  uint overflow;       // fragments that went to the tail instead of a node or slot
  uint tailShare;      // resolve: sum over pixels of the tail's share of the pixel, x 65536
  uint tailPixels;     // resolve: pixels with a tail
  uint width;          // the view's width in pixels (set by the CPU): rows of the per-pixel buffers
  uint fixedLayers;    // the fixed array (abuffer_fixed): every pixel's range is this long; 0: ranges as kept
  uint pad1, pad2;
} abufferCounters;

layout(std430, binding = 15) coherent buffer ABufferStarts { uint abufferStarts[]; };

uint abufferPixel(ivec2 p) { return uint(p.y) * abufferCounters.width + uint(p.x); }

// Counts one fragment at `p` (a counting pass's work: the counts image and
// the frame's totals); call it from a shader without derivatives (see
// abuffer_keys.frag on why atomics' results elsewhere are not trusted).
void abufferCountFragment(ivec2 p) {
  const uint c = imageAtomicAdd(uABufferCounts, p, 1u) + 1u;
  atomicAdd(abufferCounters.fragments, 1u);
  atomicMax(abufferCounters.maxPerPixel, c);
  if (c == 1u) atomicAdd(abufferCounters.coveredPixels, 1u);
}

// The length of the pixel's range: all its fragments, or the cap's share;
// the fixed array's layers whatever the pixel has.
uint abufferRangeLength(ivec2 p) {
  if (abufferCounters.fixedLayers != 0u) return abufferCounters.fixedLayers;
  return min(imageLoad(uABufferCounts, p).x, abufferCounters.perPixelCap);
}

uvec4 abufferNode(vec4 color, float depth, uint key) {
  return uvec4(packHalf2x16(color.rg), packHalf2x16(color.ba), floatBitsToUint(depth), key);
}

bool abufferWritten(uvec4 node) { return node.y != ABUFFER_UNWRITTEN; }

// The order of a pixel's range: (depth bits, key) pairs, nearer first
// (reversed Z: larger depth is nearer), then by key. The key alone orders
// depths equal in their top 24 bits by hash, which depth peeling does not
// (up to 8/255 apart at 1080p); the full depth does as peeling does.
bool abufferNearer(uvec2 a, uvec2 b) { return a.x > b.x || (a.x == b.x && a.y < b.y); }

// Whether the pixel's range was filled by the atomicMin chain (more
// fragments than nodes): then ordered by key alone, with no depth yet.
bool abufferByKey(ivec2 p, uint rangeLength) { return imageLoad(uABufferCounts, p).x > rangeLength; }
vec4 abufferColor(uvec4 node) { return vec4(unpackHalf2x16(node.x), unpackHalf2x16(node.y)); }
float abufferDepth(uvec4 node) { return uintBitsToFloat(node.z); }

#endif
