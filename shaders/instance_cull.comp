#version 450 core
// GPU culling of an instanced draw source (render/instanced_source.h): each
// instance's bounding sphere (its type's, rotated, scaled and placed)
// against every view of the frame (camera views, then shadow views; planes
// relative to the frame origin), and for each view that sees it, a slot in
// that view's list of its type: an atomic per view and type hands it out.
// The order within a list is the GPU's; every pass that draws the lists is
// order-independent except weighted blending (float sums), which can
// differ in its last bits from run to run.
layout(local_size_x = 64) in;
#include "instances.glsl"

layout(std430, binding = 19) writeonly buffer VisibleInstances { uint visibleInstances[]; };
layout(std430, binding = 20) readonly buffer TypeSpheres { vec4 typeSpheres[]; };  // xyz: centre (mesh space), w: radius
layout(std430, binding = 21) readonly buffer CullPlanes { vec4 planes[]; };        // 6 per view, unit normals
layout(std430, binding = 22) buffer VisibleCounts { uint counts[]; };              // per view and type
layout(std430, binding = 23) readonly buffer TypeBase { uint typeBase[]; };        // a type's first slot in a view's list

uniform uint uInstances;
uniform uint uViews;
uniform uint uTypes;
uniform uint uCells;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uInstances) return;
  Instance inst = instances[i];
  uint type = instanceType(inst);
  // A type or cell the source does not have, or a type whose mesh is gone
  // (radius < 0): never drawn, never read past a buffer.
  if (type >= uTypes || instanceCell(inst) >= uCells) return;
  vec4 sphere = typeSpheres[type];
  if (sphere.w < 0.0) return;
  float s = inst.positionScale.w;
  vec3 c = instanceOrigin(inst) + instanceRotation(inst) * (sphere.xyz * s);
  float radius = sphere.w * abs(s);
  for (uint v = 0u; v < uViews; ++v) {
    bool inside = true;
    for (uint k = 0u; k < 6u && inside; ++k) {
      vec4 p = planes[v * 6u + k];
      inside = dot(p.xyz, c) + p.w >= -radius;
    }
    if (!inside) continue;
    uint slot = atomicAdd(counts[v * uTypes + type], 1u);
    visibleInstances[v * uInstances + typeBase[type] + slot] = i;
  }
}
