#version 450 core
// Pass 3 of an instanced draw source's GPU culling (render/
// instanced_source.h): each instance that shaders/instance_lod.comp kept,
// at the level it chose, against every view of the frame (camera views,
// then shadow views; planes relative to the frame origin; a type that does
// not cast shadows stops after the camera views), and for each view that
// sees it, a slot in that view's part of its draw group (type, level): an
// atomic per view and group hands it out. The sphere is level 0's centre
// with a radius that holds every level, grown by the most the wind can
// move a vertex (instanceWindMargin), so culling stays conservative.
// The order within a list is the GPU's; every pass that draws the lists is
// order-independent except weighted blending (float sums), which can
// differ in its last bits from run to run.
layout(local_size_x = 64) in;
#include "instances.glsl"

layout(std430, binding = 19) writeonly buffer VisibleInstances { uint visibleInstances[]; };
layout(std430, binding = 20) readonly buffer TypeCull { InstanceTypeCull typeCull[]; };
layout(std430, binding = 21) readonly buffer CullPlanes { vec4 planes[]; };  // 6 per view, unit normals
layout(std430, binding = 22) buffer VisibleCounts { uint counts[]; };        // per view and group
layout(std430, binding = 23) readonly buffer GroupBase { uint groupBase[]; };  // a group's first slot in a view's list
layout(std430, binding = 24) readonly buffer InstanceLevels { uint instanceLevels[]; };

uniform uint uInstances;
uniform uint uViews;
uniform uint uCameraViews;
uniform uint uGroups;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uInstances) return;
  uint level = instanceLevels[i];
  if (level == 0xFFFFFFFFu) return;  // unknown type or cell, gone mesh, or beyond the cull distance
  Instance inst = instances[i];
  InstanceTypeCull t = typeCull[instanceType(inst)];
  uint group = t.info.x + level;
  vec3 s = instanceScale(inst);
  vec3 c = instanceOrigin(inst) + instanceRotation(inst) * (t.sphere.xyz * s);
  float radius = t.cull.x * max(abs(s.x), abs(s.z)) + t.cull.z * abs(s.z);
  uint views = t.info.z != 0u ? uViews : uCameraViews;
  for (uint v = 0u; v < views; ++v) {
    bool inside = true;
    for (uint k = 0u; k < 6u && inside; ++k) {
      vec4 p = planes[v * 6u + k];
      inside = dot(p.xyz, c) + p.w >= -radius;
    }
    if (!inside) continue;
    uint slot = atomicAdd(counts[v * uGroups + group], 1u);
    visibleInstances[v * uInstances + groupBase[group] + slot] = i;
  }
}
