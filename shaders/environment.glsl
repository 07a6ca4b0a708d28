// Light from the sky and the surroundings (everything but the direct
// lights): a hemisphere between the ground and the sky's zenith colour.
#ifndef HS_ENVIRONMENT_GLSL
#define HS_ENVIRONMENT_GLSL
#include "frame_blocks.glsl"
#include "surface.glsl"

vec3 ambientLighting(Surface s) {
  float up = s.normal.z * 0.5 + 0.5;
  return s.albedo * mix(frame.groundColor.rgb, frame.skyZenith.rgb, up) * frame.params.x;
}

#endif
