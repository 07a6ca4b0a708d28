#version 450 core
// The A-buffer's key pass (render/abuffer.h): each fragment takes a node in
// its pixel's range and writes its depth and key there
// (abuffer_key_store.glsl says how, and why there); abuffer_sort_keys.comp
// then sorts each range, and the lit pass (oit_main.glsl) finds its node
// by binary search on them and writes its colour.
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
#include "abuffer_key_store.glsl"
flat in uint vObject;

void main() {
  if (gl_HelperInvocation) return;  // stores nothing (oit_main.glsl)
#ifdef INSTANCED
  instanceFadeDiscard();
#endif
#ifdef HS_PARTICLE
  particleCoverDiscard();
#endif
  abufferKeyFragment(ivec2(gl_FragCoord.xy), gl_FragCoord.z, oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID)));
}
