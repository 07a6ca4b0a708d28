// Atmosphere between a surface and the eye.
#ifndef HS_FOG_GLSL
#define HS_FOG_GLSL
#include "frame_blocks.glsl"

vec3 applyFog(vec3 color, vec3 p) { return color; }

#endif
