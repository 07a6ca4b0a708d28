// Reflectance of a surface for one light direction: the response to a unit
// irradiance arriving from `l`, times cos(theta) (so a caller multiplies by
// the light's colour and attenuation only). Scaled so that a white Lambert
// surface facing the light returns 1 (the 1/pi of a BRDF is folded into
// the lights' intensity, as before materials had models), and every model
// shares that scale: their diffuse parts agree, their highlights differ.
//
// The survey's models: Lambert (diffuse only), Phong (specular from the
// reflection vector, ks (R.V)^n) and Blinn-Phong (from the half vector,
// ks (N.H)^n), both added to Lambert. The default is physically based:
// GGX (Trowbridge-Reitz) microfacet distribution, height-correlated Smith
// visibility, Schlick's Fresnel, and a diffuse part weighted by what the
// specular reflection and the metal leave (energy conserving), as in
// Filament and Unreal.
#ifndef HS_BRDF_GLSL
#define HS_BRDF_GLSL
#include "surface.glsl"

const float HS_PI = 3.14159265358979;

float ggxDistribution(float ndh, float a) {
  float a2 = a * a;
  float d = ndh * ndh * (a2 - 1.0) + 1.0;
  return a2 / max(HS_PI * d * d, 1e-8);
}

// Smith's height-correlated visibility, V = G / (4 N.L N.V).
float smithVisibility(float ndv, float ndl, float a) {
  float a2 = a * a;
  float gv = ndl * sqrt(ndv * ndv * (1.0 - a2) + a2);
  float gl = ndv * sqrt(ndl * ndl * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-6);
}

vec3 schlickFresnel(vec3 f0, float vdh) {
  float f = pow(1.0 - vdh, 5.0);
  return f0 + (vec3(1.0) - f0) * f;
}

vec3 pbrReflect(Surface s, vec3 l, float ndl) {
  vec3 h = normalize(l + s.view);
  float ndv = max(dot(s.normal, s.view), 1e-4);
  float ndh = max(dot(s.normal, h), 0.0);
  float vdh = max(dot(s.view, h), 0.0);
  // Perceptual roughness squared; a floor keeps a mirror's highlight finite.
  float a = max(s.roughness * s.roughness, 0.002);
  // Dielectric F0 from `specular` (0.5 -> 4%), metals reflect their colour.
  vec3 f0 = mix(vec3(0.16 * s.specular * s.specular), s.albedo, s.metallic);
  vec3 f = schlickFresnel(f0, vdh);
  vec3 spec = ggxDistribution(ndh, a) * smithVisibility(ndv, ndl, a) * f;
  vec3 diffuse = (vec3(1.0) - f) * (1.0 - s.metallic) * s.albedo;
  // x pi: the scale of the header (a white Lambert surface returns 1).
  return (diffuse + spec * HS_PI) * ndl;
}

vec3 reflectLight(Surface s, vec3 l) {
  float ndl = dot(s.normal, l);
  if (ndl <= 0.0) return vec3(0.0);
  if (s.model == MODEL_LAMBERT) return s.albedo * ndl;
  if (s.model == MODEL_PHONG) {
    vec3 r = reflect(-l, s.normal);
    return s.albedo * ndl + vec3(s.specular * pow(max(dot(r, s.view), 0.0), s.shininess));
  }
  if (s.model == MODEL_BLINN_PHONG) {
    vec3 h = normalize(l + s.view);
    return s.albedo * ndl + vec3(s.specular * pow(max(dot(s.normal, h), 0.0), s.shininess));
  }
  return pbrReflect(s, l, ndl);
}

#endif
