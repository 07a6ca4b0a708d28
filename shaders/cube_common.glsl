// Cube map texels as directions (GL's face order and orientation), shared
// by the environment's compute shaders; render/sh_irradiance.cpp is the
// same on the CPU.
#ifndef HS_CUBE_COMMON_GLSL
#define HS_CUBE_COMMON_GLSL

vec3 cubeTexelDirection(int face, ivec2 p, int size) {
  vec2 st = 2.0 * (vec2(p) + 0.5) / float(size) - 1.0;
  float s = st.x, t = st.y;
  vec3 d;
  if (face == 0) d = vec3(1.0, -t, -s);
  else if (face == 1) d = vec3(-1.0, -t, s);
  else if (face == 2) d = vec3(s, 1.0, t);
  else if (face == 3) d = vec3(s, -1.0, -t);
  else if (face == 4) d = vec3(s, -t, 1.0);
  else d = vec3(-s, -t, -1.0);
  return normalize(d);
}

float cubeAreaElement(float x, float y) { return atan(x * y, sqrt(x * x + y * y + 1.0)); }

float cubeTexelSolidAngle(ivec2 p, int size) {
  float inv = 1.0 / float(size);
  float x0 = 2.0 * float(p.x) * inv - 1.0, x1 = x0 + 2.0 * inv;
  float y0 = 2.0 * float(p.y) * inv - 1.0, y1 = y0 + 2.0 * inv;
  return cubeAreaElement(x0, y0) - cubeAreaElement(x0, y1) - cubeAreaElement(x1, y0) + cubeAreaElement(x1, y1);
}

#endif
