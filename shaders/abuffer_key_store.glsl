// The A-buffer key pass's work for one fragment (abuffer_keys.frag, and
// impostor.frag's IMPOSTOR_ABUFFER_KEYS variant, whose depth is the one it
// computes, not gl_FragCoord.z): take a node in the pixel's range
// (abuffer_scan.comp made the ranges) and write the fragment's depth and
// key there. Nodes are handed out here, in a shader without derivatives,
// because on llvmpipe the value an atomic returns in the lit shader (which
// has helper invocations for its derivatives) can belong to another lane:
// linked lists built there lost and doubled fragments from run to run.
// Nothing in the lit pass depends on an atomic's result, so the A-buffer
// is the same every frame whatever order fragments arrive in.
//
// A pixel with more fragments than the cap gives it (render/abuffer.cpp
// sizes the cap from the memory limit) keeps its nearest ones instead,
// through the K-buffer's atomicMin chain (oit_kbuffer.glsl): which ones it
// keeps does not depend on arrival order either; such a range is ordered
// by key alone (abufferByKey). The others reach the tail in the lit pass.
// Needs oit_kbuffer.glsl's key (OIT_KEY_ONLY), included before it.
#ifndef HS_ABUFFER_KEY_STORE_GLSL
#define HS_ABUFFER_KEY_STORE_GLSL

#include "abuffer.glsl"
layout(std430, binding = 16) coherent buffer ABufferCursor { uint abufferCursor[]; };

void abufferKeyFragment(ivec2 p, float depth, uint key) {
  const uint pixel = abufferPixel(p);
  const uint start = abufferStarts[pixel], kept = abufferStarts[pixel + 1u] - start;
  if (imageLoad(uABufferCounts, p).x <= kept) {
    // Room for every fragment: any order will do, the sort follows.
    const uint slot = atomicAdd(abufferCursor[pixel], 1u);
    if (slot < kept) abufferNodes[start + slot].zw = uvec2(floatBitsToUint(depth), key);
    return;
  }
  for (uint i = 0u; i < kept; ++i) {
    const uint old = atomicMin(abufferNodes[start + i].w, key);
    if (old == OIT_KEY_EMPTY) return;  // an empty node took it
    key = max(old, key);               // the larger one moves on
  }
}

#endif
