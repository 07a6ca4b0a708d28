// The A-buffer: per-pixel linked lists of fragments (Yang et al. 2010).
// render/abuffer.h is the C++ side; the bindings and layouts must match.
//   buffer 15     heads   uint per pixel (row-major, abufferPixel): the pixel's newest
//                         node, ABUFFER_END for none
//   image unit 1  counts  r32ui: fragments per pixel (the counting pass; depth complexity)
//   buffer 12     nodes   uvec4 per fragment: x packHalf2x16(r, g), y packHalf2x16(b, a)
//                         (straight colour, linear HDR, and opacity), z depth bits, w next node
//   buffer 13     ABufferCounters (below)
//   buffer 14     tail    (with a tail) 4 uints per pixel: what did not fit the pool
//                         (oit_tail.glsl), order-independent integer sums
// The heads are a buffer, not an r32ui image: on llvmpipe the image atomics
// of a shader that takes derivatives also run in helper invocations (pixels
// next to the triangle, shaded only for their neighbours' derivatives) even
// when they test gl_HelperInvocation, which linked nodes that were never
// written; buffer atomics are masked as they should be.
// Depth is gl_FragCoord.z in the renderer's reversed Z (1 near, 0 far):
// non-negative floats, so their bits compare like the floats.
#ifndef HS_ABUFFER_GLSL
#define HS_ABUFFER_GLSL

#define ABUFFER_END 0xFFFFFFFFu

layout(binding = 1, r32ui) uniform coherent uimage2D uABufferCounts;

layout(std430, binding = 12) coherent buffer ABufferNodes { uvec4 abufferNodes[]; };

// Filled by the counting pass (fragments, maxPerPixel, coveredPixels), the
// CPU (capacity) and the capture (allocated: nodes asked for, which passes
// capacity by the overflow); the tail and resolve add theirs.
layout(std430, binding = 13) coherent buffer ABufferCounters {
  uint allocated;      // nodes the capture asked for (over capacity: overflow)
  uint fragments;      // the counting pass: fragments in all
  uint maxPerPixel;    // the counting pass: the deepest pixel
  uint coveredPixels;  // the counting pass: pixels with at least one fragment
  uint capacity;       // nodes in the pool (set by the CPU before the capture)
  uint overflow;       // fragments that went to the tail instead of a list or slot
  uint tailShare;      // resolve: sum over pixels of the tail's share of the pixel, x 65536
  uint tailPixels;     // resolve: pixels with a tail
  uint width;          // the view's width in pixels (set by the CPU): rows of the per-pixel buffers
  uint pad0, pad1, pad2;
} abufferCounters;

layout(std430, binding = 15) coherent buffer ABufferHeads { uint abufferHeads[]; };

uint abufferPixel(ivec2 p) { return uint(p.y) * abufferCounters.width + uint(p.x); }

uvec4 abufferPack(vec4 color, float depth) {
  return uvec4(packHalf2x16(color.rg), packHalf2x16(color.ba), floatBitsToUint(depth), ABUFFER_END);
}

vec4 abufferColor(uvec4 node) { return vec4(unpackHalf2x16(node.x), unpackHalf2x16(node.y)); }
float abufferDepth(uvec4 node) { return uintBitsToFloat(node.z); }

#endif
