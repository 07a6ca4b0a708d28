// The lighting of every lit surface (meshes, terrain; later foliage and
// particles), written once and split by concern:
//   surface.glsl      what a material's shader fills in
//   brdf.glsl         the lighting models (reflectance for one direction)
//   lights.glsl       direct light from the sun and the scene's lights
//   shadows.glsl      visibility of each light
//   environment.glsl  sky and surroundings (ambient)
//   fog.glsl          atmosphere towards the eye
#ifndef HS_LIGHTING_GLSL
#define HS_LIGHTING_GLSL
#include "environment.glsl"
#include "fog.glsl"
#include "lights.glsl"

// The ambient term's share of the last shadeSurface() result's luminance:
// the scene colour's alpha, which the AO pass reads to occlude the ambient
// light only (shaders/ssao_apply.frag).
float hsAmbientShare = 0.0;

vec3 shadeSurface(Surface s) {
  vec3 ambient = ambientLighting(s);
  vec3 lit = s.emission + directLighting(s) + ambient;
  const vec3 luma = vec3(0.2126, 0.7152, 0.0722);
  hsAmbientShare = clamp(dot(ambient, luma) / max(dot(lit, luma), 1e-6), 0.0, 1.0);
  return applyFog(lit, s.position);
}

// A Blinn-Phong surface from its colour, position, normal and highlight
// (what the mesh and terrain shaders pass today).
vec3 lightSurface(vec3 albedo, vec3 p, vec3 n, float shininess, float specular) {
  Surface s;
  s.position = p;
  s.normal = n;
  s.view = normalize(-p);
  s.albedo = albedo;
  s.roughness = 0.5;
  s.metallic = 0.0;
  s.specular = specular;
  s.shininess = shininess;
  s.emission = vec3(0.0);
  s.transmission = 0.0;
  s.model = MODEL_BLINN_PHONG;
  return shadeSurface(s);
}

#endif
