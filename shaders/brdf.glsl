// Reflectance of a surface for one light direction: the radiance it sends
// towards the eye per unit of illuminance arriving from `l` (measured
// facing the light), i.e. BRDF x cos(theta), so a caller multiplies by the
// light's colour and attenuation only. Physical units: a white Lambert
// surface facing a light of illuminance E returns E/pi (cd/m² from lux,
// both in scene units, scene/light_units.h), as in Filament and Unreal;
// the image-based light (environment.glsl) is in the same units.
//
// The survey's models: Lambert (albedo/pi), Phong (specular from the
// reflection vector) and Blinn-Phong (from the half vector), both added to
// Lambert. Their lobes are the survey's and have no energy normalisation:
// the specular part returned is ks (R.V)^n / pi (Phong) or ks (N.H)^n / pi
// (Blinn-Phong), with no cos(theta) (the survey's lobe; its BRDF is that
// over cos(theta)), so a highlight of ks = 1 peaks as bright as a white
// Lambert surface facing the light, at any exponent. The factors that
// would conserve energy (a BRDF ks (n+2)/2pi (R.V)^n for Phong, about
// ks (n+8)/8pi (N.H)^n for Blinn-Phong) are not applied: highlights would
// get about (n+2)/2 times brighter (17x at n = 32) than in the survey's
// comparison views and in the materials made with them; PBR is the model
// that conserves energy.
// The default is physically based: GGX (Trowbridge-Reitz) microfacet
// distribution, height-correlated Smith visibility, Schlick's Fresnel, and
// a Lambert diffuse part weighted by what the specular reflection and the
// metal leave (energy conserving), as in Filament and Unreal.
//
// Transmission (Surface.transmission t, thin two-sided surfaces: leaves):
// of the diffuse light, t passes through and 1 - t is reflected. Lit from
// the other side (N.L < 0) the surface returns t x albedo x |N.L| / pi,
// Lambert on the far side (a leaf's scattering blurs any direction); lit
// from the eye's side its diffuse part (Lambert's, or PBR's) is 1 - t of
// an opaque one's, the specular part unchanged. t = 0 is the opaque
// surface, bit for bit.
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
  vec3 diffuse = (vec3(1.0) - f) * (1.0 - s.metallic) * s.albedo / HS_PI;
  if (s.transmission > 0.0) diffuse *= 1.0 - s.transmission;
  return (diffuse + spec) * ndl;
}

vec3 reflectLight(Surface s, vec3 l) {
  float ndl = dot(s.normal, l);
  if (ndl <= 0.0) return s.transmission > 0.0 ? s.albedo * (s.transmission * -ndl / HS_PI) : vec3(0.0);
  vec3 lambert = s.albedo * (ndl / HS_PI);
  if (s.transmission > 0.0) lambert *= 1.0 - s.transmission;
  if (s.model == MODEL_LAMBERT) return lambert;
  if (s.model == MODEL_PHONG) {
    vec3 r = reflect(-l, s.normal);
    return lambert + vec3(s.specular * pow(max(dot(r, s.view), 0.0), s.shininess) / HS_PI);
  }
  if (s.model == MODEL_BLINN_PHONG) {
    vec3 h = normalize(l + s.view);
    return lambert + vec3(s.specular * pow(max(dot(s.normal, h), 0.0), s.shininess) / HS_PI);
  }
  return pbrReflect(s, l, ndl);
}

#endif
