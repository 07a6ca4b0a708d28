#version 450 core
// The A-buffer's counting pass (render/abuffer.h): each fragment of the
// captured draws that passes the depth test adds one to its pixel's count
// (the depth complexity) and to the frame's totals, from which the CPU
// sizes the node pool before the capture draws the same fragments again.
// Early tests: a fragment behind the opaque depth must not count.
layout(early_fragment_tests) in;
#ifdef INSTANCED
#include "instance_fade.glsl"  // the lit pass drops the same fragments
#endif
#ifdef HS_PARTICLE
#include "particle_cover.glsl"  // particle.frag drops the same fragments
#endif
#include "abuffer.glsl"

void main() {
  if (gl_HelperInvocation) return;  // stores nothing (oit_main.glsl)
#ifdef INSTANCED
  instanceFadeDiscard();
#endif
#ifdef HS_PARTICLE
  particleCoverDiscard();
#endif
  abufferCountFragment(ivec2(gl_FragCoord.xy));
}
