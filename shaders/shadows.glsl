// How much of a light reaches a point (1: lit, 0: in shadow).
#ifndef HS_SHADOWS_GLSL
#define HS_SHADOWS_GLSL
#include "frame_blocks.glsl"

float sunVisibility(vec3 p, vec3 n) { return 1.0; }
float lightVisibility(int light, vec3 p, vec3 n) { return 1.0; }

#endif
