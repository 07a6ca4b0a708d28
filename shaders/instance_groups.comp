#version 450 core
// Pass 2 of an instanced draw source's GPU culling (render/
// instanced_source.h): each draw group's first slot in a view's list, the
// sum of the groups' totals before it (shaders/instance_lod.comp counted
// them). A view's list holds each instance at most once, so views * n slots
// hold every view's lists. One invocation: a frame has a few dozen groups
// (types x levels).
layout(local_size_x = 1) in;

layout(std430, binding = 23) writeonly buffer GroupBase { uint groupBase[]; };
layout(std430, binding = 25) readonly buffer GroupTotals { uint groupTotals[]; };

uniform uint uGroups;

void main() {
  uint sum = 0u;
  for (uint g = 0u; g < uGroups; ++g) {
    groupBase[g] = sum;
    sum += groupTotals[g];
  }
}
