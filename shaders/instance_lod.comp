#version 450 core
// Pass 1 of an instanced draw source's GPU culling (render/
// instanced_source.h): per instance, once per frame, whether it is beyond
// its type's cull distance from the LOD eye (then no view draws it), else
// its level of detail by render/mesh_lod.h chooseMeshLod's rule: the
// coarsest level whose error, projected at the distance from the LOD eye to
// the instance's bounding sphere (level 0's bounds, rotated, scaled,
// placed), is within the frame's pixel bound. The CPU turned each level's
// error into the distance from which it passes (in the mesh's own metres:
// the distance here is divided by the instance's largest scale, as
// chooseMeshLod does); the CPU path asks chooseMeshLod itself, in double.
// Writes the level (0xFFFFFFFF: culled) and counts each draw group's
// instances (a group: a type and a level).
layout(local_size_x = 64) in;
#include "instances.glsl"

layout(std430, binding = 20) readonly buffer TypeCull { InstanceTypeCull typeCull[]; };
layout(std430, binding = 24) writeonly buffer InstanceLevels { uint instanceLevels[]; };
layout(std430, binding = 25) buffer GroupTotals { uint groupTotals[]; };
layout(std430, binding = 26) readonly buffer LodDistances { float lodDistances[]; };  // per group

uniform uint uInstances;
uniform uint uTypes;
uniform uint uCells;
uniform vec3 uLodEye;      // relative to the frame origin
uniform float uCullSlack;  // 1 + a hair: mesh.vert's fade drops what lies between

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uInstances) return;
  Instance inst = instances[i];
  uint type = instanceType(inst);
  uint level = 0xFFFFFFFFu;
  // A type or cell the source does not have, or a type whose mesh is gone
  // (radius < 0): never drawn, never read past a buffer.
  if (type < uTypes && instanceCell(inst) < uCells) {
    InstanceTypeCull t = typeCull[type];
    vec3 origin = instanceOrigin(inst);
    if (t.sphere.w >= 0.0 && (!(t.cull.y > 0.0) || length(origin - uLodEye) <= t.cull.y * uCullSlack)) {
      vec3 s = instanceScale(inst);
      float largest = max(abs(s.x), abs(s.z));
      float scale = largest > 0.0 && !isinf(largest) ? largest : 1.0;
      vec3 centre = origin + instanceRotation(inst) * (t.sphere.xyz * s);
      float d = max(0.0, length(centre - uLodEye) - t.sphere.w * scale);
      level = 0u;
      if (d > 0.0) {
        float unscaled = d / scale;
        // Errors grow along the chain: the first level that fails ends it.
        for (uint l = 1u; l < t.info.y; ++l) {
          if (!(unscaled >= lodDistances[t.info.x + l])) break;
          level = l;
        }
      }
      atomicAdd(groupTotals[t.info.x + level], 1u);
    }
  }
  instanceLevels[i] = level;
}
