#version 450 core
// The radiance cube projected onto 9 spherical harmonics (l <= 2), each
// texel weighted by its solid angle, then convolved with the clamped
// cosine (Ramamoorthi and Hanrahan) and divided by pi: the coefficients
// environment.glsl sums give E(n)/pi, what a white Lambertian surface
// reflects. One work group; render/sh_irradiance.cpp is the CPU twin.
#include "cube_common.glsl"
layout(local_size_x = 64) in;
layout(rgba16f, binding = 0) uniform readonly imageCube uCube;
layout(std430, binding = 0) writeonly buffer EnvOut { vec4 sh[9]; } outBlock;
uniform int uSize;

shared vec3 partial[64][9];

void main() {
  uint tid = gl_LocalInvocationIndex;
  vec3 acc[9];
  for (int k = 0; k < 9; ++k) acc[k] = vec3(0.0);
  int perFace = uSize * uSize;
  for (int i = int(tid); i < 6 * perFace; i += 64) {
    int face = i / perFace, j = i - face * perFace;
    ivec2 p = ivec2(j % uSize, j / uSize);
    vec3 d = cubeTexelDirection(face, p, uSize);
    vec3 r = imageLoad(uCube, ivec3(p, face)).rgb * cubeTexelSolidAngle(p, uSize);
    acc[0] += r * 0.282095;
    acc[1] += r * (0.488603 * d.y);
    acc[2] += r * (0.488603 * d.z);
    acc[3] += r * (0.488603 * d.x);
    acc[4] += r * (1.092548 * d.x * d.y);
    acc[5] += r * (1.092548 * d.y * d.z);
    acc[6] += r * (0.315392 * (3.0 * d.z * d.z - 1.0));
    acc[7] += r * (1.092548 * d.x * d.z);
    acc[8] += r * (0.546274 * (d.x * d.x - d.y * d.y));
  }
  for (int k = 0; k < 9; ++k) partial[tid][k] = acc[k];
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1u) {
    if (tid < stride)
      for (int k = 0; k < 9; ++k) partial[tid][k] += partial[tid + stride][k];
    barrier();
  }
  if (tid < 9u) {
    float A = tid == 0u ? 1.0 : (tid < 4u ? 2.0 / 3.0 : 0.25);  // A_l / pi
    outBlock.sh[tid] = vec4(partial[0][tid] * A, 0.0);
  }
}
