// Reflectance of a surface for one light direction: the response to a unit
// irradiance arriving from `l`, times cos(theta) (so a caller multiplies by
// the light's colour and attenuation only).
#ifndef HS_BRDF_GLSL
#define HS_BRDF_GLSL
#include "surface.glsl"

vec3 reflectLight(Surface s, vec3 l) {
  float ndl = max(dot(s.normal, l), 0.0);
  if (ndl <= 0.0) return vec3(0.0);
  vec3 h = normalize(l + s.view);
  float spec = pow(max(dot(s.normal, h), 0.0), s.shininess) * s.specular;
  return s.albedo * ndl + vec3(spec);
}

#endif
