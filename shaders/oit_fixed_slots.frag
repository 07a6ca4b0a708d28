#version 450 core
// abuffer_fixed pass 1 (render/oit.cpp): each fragment takes the pixel's
// next layer of the fixed array (OIT_FIXED_LAYERS) and writes its key
// into that layer of the key array (oit_kbuffer.glsl's oitKey); the lit pass then finds its layer by
// that key. Layers are handed out here, in a shader without derivatives,
// because on llvmpipe the value an atomic returns in the lit shader (which
// has helper invocations) can belong to another lane (abuffer_link.comp).
// Counts the frame's fragments like the counting pass.
layout(early_fragment_tests) in;
#include "abuffer.glsl"
#define OIT_KEY_ONLY
#include "oit_kbuffer.glsl"
layout(std430, binding = 15) coherent buffer OitFixedCount { uint oitFixedCount[]; };
layout(binding = 2, r32ui) uniform coherent uimage2DArray uOitFixedKeys;
flat in uint vObject;

void main() {
  if (gl_HelperInvocation) return;
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const uint i = atomicAdd(oitFixedCount[abufferPixel(p)], 1u);
  atomicAdd(abufferCounters.fragments, 1u);
  atomicMax(abufferCounters.maxPerPixel, i + 1u);
  if (i == 0u) atomicAdd(abufferCounters.coveredPixels, 1u);
  if (i < uint(OIT_FIXED_LAYERS))
    imageStore(uOitFixedKeys, ivec3(p, int(i)), uvec4(oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID))));
}
