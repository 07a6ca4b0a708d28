// The compact per-instance format of instanced draw sources
// (render/instanced_source.h GpuInstance, 32 bytes; the layouts must match
// member for member): a position relative to its cell's origin, the scale
// as two halves (across: mesh x and y; along the height: mesh z), a
// rotation as a unit quaternion in four snorm16, the instance's type and
// cell, and its stable id (picking, the transparency key, the wind's
// phase). Cell origins are relative to the frame origin, formed in double
// on the CPU, so an instance far from the world origin arrives as small
// floats. Also the wind (instanceWindOffset; the C++ copy in
// instanced_source.cpp is the same model) and the per-type data the
// culling passes read (InstanceTypeCull).
// Storage bindings 17 (instances), 18 (cells), 19 (the visible instances of
// each view, by draw group, written by shaders/instance_cull.comp or the
// CPU), 23 (each draw group's first slot in a view's list).
#ifndef HS_INSTANCES_GLSL
#define HS_INSTANCES_GLSL

struct Instance {
  vec4 positionScale;    // xyz: relative to the cell origin (m); w: the bits of packHalf2x16(scale xy, scale z)
  uvec4 rotationTypeId;  // xy: quaternion (x, y | z, w) as snorm16 pairs; z: type | cell << 16; w: stable id
};
layout(std430, binding = 17) readonly buffer InstanceBlock { Instance instances[]; };
layout(std430, binding = 18) readonly buffer InstanceCellBlock { vec4 instanceCells[]; };

// A type as the culling passes see it (instanced_source.cpp GpuTypeCull).
struct InstanceTypeCull {
  vec4 sphere;  // level 0's bounds: centre (mesh space), radius; w < 0: the type draws nothing
  vec4 cull;    // x: radius about the same centre holding every level; y: cull distance (0: none);
                // z: wind margin per unit |scale z|
  uvec4 info;   // x: first draw group, y: levels (one group each), z: 1 casts shadows
};

uint instanceType(Instance i) { return i.rotationTypeId.z & 0xFFFFu; }
uint instanceCell(Instance i) { return i.rotationTypeId.z >> 16; }

// The scale per mesh axis: (across, across, height).
vec3 instanceScale(Instance i) {
  vec2 s = unpackHalf2x16(floatBitsToUint(i.positionScale.w));
  return vec3(s.x, s.x, s.y);
}

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

// The wind's phase per instance id: lowbias32.glsl.
#include "lowbias32.glsl"

// The wind's move of a vertex `height` metres above the instance's origin
// (mesh z, before scale) of a mesh `meshHeight` tall on an instance scaled
// by `scaleZ` along z, with the type's `response`, at the frame's `time`
// (FrameBlock.time): render/instanced_source.h instanceWindOffset has the
// model. Seconds are folded to t mod 60 s (every frequency is a multiple of
// 1/60 Hz) from the whole seconds and the fraction taken in double, so a
// late frame sways as exactly as an early one.
const vec2 kInstanceWindDirection = vec2(0.8, 0.6);
const float kInstanceWindBend = 0.02;
vec3 instanceWindOffset(float response, float height, float meshHeight, float scaleZ, uint id, vec4 time) {
  const float tau = 6.28318531;
  float h = clamp(height / meshHeight, 0.0, 1.0);
  float worldHeight = meshHeight * abs(scaleZ);
  float phase = tau * float(lowbias32(id) >> 8) * (1.0 / 16777216.0);
  float t = mod(round(time.x - time.z), 60.0) + time.z;
  float bend = 0.6 + 0.4 * sin(tau * fract(0.5 * t) + phase);
  float gust = 0.3 * sin(tau * fract(1.3 * t) + 1.7 * phase) * (0.5 + 0.5 * sin(tau * fract(0.2 * t) + 0.5 * phase));
  vec2 across = vec2(-kInstanceWindDirection.y, kInstanceWindDirection.x);
  vec2 move = kInstanceWindBend * response * worldHeight * h * h * (kInstanceWindDirection * bend + across * gust);
  float stem = h * worldHeight;
  float drop = stem > 0.0 ? dot(move, move) / (2.0 * stem) : 0.0;
  return vec3(move, -drop);
}

// The share of the instance's pixels its fade drops (0: all drawn, 1:
// none): 1 from `cullDistance` metres from the LOD eye on, falling
// linearly to 0 over the `fadeLength` metres before it; 0 with no cull
// distance. `distance` is from the LOD eye to the instance's origin.
float instanceFade(float distance, float cullDistance, float fadeLength) {
  if (!(cullDistance > 0.0)) return 0.0;
  if (distance >= cullDistance) return 1.0;
  if (!(fadeLength > 0.0)) return 0.0;
  return clamp((distance - (cullDistance - fadeLength)) / fadeLength, 0.0, 1.0);
}

#endif
