#version 450 core
// The A-buffer's key pass (render/abuffer.h): each fragment takes a node in
// its pixel's range (abuffer_scan.comp made the ranges) and writes its
// depth and key there; abuffer_sort_keys.comp then sorts each range, and
// the lit pass (oit_main.glsl) finds its node by binary search on them and
// writes its colour. Nodes are handed out here, in a shader without
// derivatives, because on llvmpipe the value an atomic returns in the lit
// shader (which has helper invocations for its derivatives) can belong to
// another lane: linked lists built there lost and doubled fragments from
// run to run. Nothing in the lit pass depends on an atomic's result, so
// the A-buffer is the same every frame whatever order fragments arrive in.
//
// A pixel with more fragments than the cap gives it (render/abuffer.cpp
// sizes the cap from the memory limit) keeps its nearest ones instead,
// through the K-buffer's atomicMin chain (oit_kbuffer.glsl): which ones it
// keeps does not depend on arrival order either; such a range is ordered
// by key alone (abufferByKey). The others reach the tail in the lit pass.
layout(early_fragment_tests) in;
#ifdef INSTANCED
#include "instance_fade.glsl"  // the lit pass drops the same fragments
#endif
#ifdef HS_PARTICLE
#include "particle_cover.glsl"  // particle.frag drops the same fragments
#endif
#include "abuffer.glsl"
#define OIT_KEY_ONLY
#include "oit_kbuffer.glsl"
layout(std430, binding = 16) coherent buffer ABufferCursor { uint abufferCursor[]; };
flat in uint vObject;

void main() {
  if (gl_HelperInvocation) return;  // stores nothing (oit_main.glsl)
#ifdef INSTANCED
  instanceFadeDiscard();
#endif
#ifdef HS_PARTICLE
  particleCoverDiscard();
#endif
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const uint pixel = abufferPixel(p);
  const uint start = abufferStarts[pixel], kept = abufferStarts[pixel + 1u] - start;
  uint key = oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID));
  if (imageLoad(uABufferCounts, p).x <= kept) {
    // Room for every fragment: any order will do, the sort follows.
    const uint slot = atomicAdd(abufferCursor[pixel], 1u);
    if (slot < kept) abufferNodes[start + slot].zw = uvec2(floatBitsToUint(gl_FragCoord.z), key);
    return;
  }
  for (uint i = 0u; i < kept; ++i) {
    const uint old = atomicMin(abufferNodes[start + i].w, key);
    if (old == OIT_KEY_EMPTY) return;  // an empty node took it
    key = max(old, key);               // the larger one moves on
  }
}
