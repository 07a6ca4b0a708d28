// The compact per-instance format of instanced draw sources
// (render/instanced_source.h GpuInstance, 32 bytes; the layouts must match
// member for member): a position relative to its cell's origin, a uniform
// scale, a rotation as a unit quaternion in four snorm16, the instance's
// type and cell, and its stable id (picking, the transparency key). Cell
// origins are relative to the frame origin, formed in double on the CPU,
// so an instance far from the world origin arrives as small floats.
// Storage bindings 17 (instances), 18 (cells), 19 (the visible instances of
// each view and type, written by shaders/instance_cull.comp or the CPU).
#ifndef HS_INSTANCES_GLSL
#define HS_INSTANCES_GLSL

struct Instance {
  vec4 positionScale;    // xyz: relative to the cell origin (m); w: uniform scale
  uvec4 rotationTypeId;  // xy: quaternion (x, y | z, w) as snorm16 pairs; z: type | cell << 16; w: stable id
};
layout(std430, binding = 17) readonly buffer InstanceBlock { Instance instances[]; };
layout(std430, binding = 18) readonly buffer InstanceCellBlock { vec4 instanceCells[]; };

uint instanceType(Instance i) { return i.rotationTypeId.z & 0xFFFFu; }
uint instanceCell(Instance i) { return i.rotationTypeId.z >> 16; }

// The rotation matrix of the stored quaternion (renormalised: snorm16
// rounding leaves it up to about 2e-5 off unit length).
mat3 instanceRotation(Instance i) {
  vec4 q = normalize(vec4(unpackSnorm2x16(i.rotationTypeId.x), unpackSnorm2x16(i.rotationTypeId.y)));
  float x = q.x, y = q.y, z = q.z, w = q.w;
  return mat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + z * w), 2.0 * (x * z - y * w),
              2.0 * (x * y - z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + x * w),
              2.0 * (x * z + y * w), 2.0 * (y * z - x * w), 1.0 - 2.0 * (x * x + y * y));
}

// The instance's origin relative to the frame origin.
vec3 instanceOrigin(Instance i) { return instanceCells[instanceCell(i)].xyz + i.positionScale.xyz; }

#endif
