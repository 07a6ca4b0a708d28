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

vec3 shadeSurface(Surface s) {
  return applyFog(s.emission + directLighting(s) + ambientLighting(s), s.position);
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
  s.model = MODEL_BLINN_PHONG;
  return shadeSurface(s);
}

#endif
