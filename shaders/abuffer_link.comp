#version 450 core
// Links the nodes the capture appended (render/abuffer.h) into their
// pixels' lists: node i's .w holds its pixel until here and its next node
// after. Done apart from the capture because on llvmpipe the values atomics
// return in a fragment shader that has helper invocations (one that takes
// derivatives, as the lit mesh shader does) can belong to another lane:
// an atomicExchange there linked a node to another pixel's list. The
// capture's own atomicAdd only has to hand out distinct indices.
layout(local_size_x = 64) in;
#include "abuffer.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= min(abufferCounters.allocated, abufferCounters.capacity)) return;
  const uint pixel = abufferNodes[i].w;
  abufferNodes[i].w = atomicExchange(abufferHeads[pixel], i);
}
