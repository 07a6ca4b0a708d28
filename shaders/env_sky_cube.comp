#version 450 core
// The analytic sky (without the sun's disc: the sun light is the direct
// term) into level 0 of the environment's radiance cube.
#include "sky_model.glsl"
#include "cube_common.glsl"
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) uniform writeonly imageCube uCube;
uniform int uSize;

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= uSize || id.y >= uSize) return;
  imageStore(uCube, id, vec4(skyRadiance(cubeTexelDirection(id.z, id.xy, uSize)), 1.0));
}
