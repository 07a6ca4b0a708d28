#version 450 core
// K-buffer pass 1 (oit_kbuffer.glsl): the fragment's key into the pixel's
// K sorted slots; also counts the pixel's fragments (depth complexity).
layout(early_fragment_tests) in;
#ifdef INSTANCED
#include "instance_fade.glsl"  // the lit pass drops the same fragments
#endif
#ifdef HS_PARTICLE
#include "particle_cover.glsl"  // particle.frag drops the same fragments
#endif
#include "abuffer.glsl"
#include "oit_kbuffer.glsl"
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
  abufferCountFragment(p);
  uint v = oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID));
  for (int i = 0; i < OIT_K; ++i) {
    const uint old = imageAtomicMin(uOitSlots, ivec3(p, i), v);
    if (old == OIT_KEY_EMPTY) return;  // an empty slot took it
    v = max(old, v);                   // the larger one moves on
  }
}
