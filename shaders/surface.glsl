// A point of a surface as the lighting sees it, filled by each material's
// shader (meshes, terrain; later foliage and particles). Eye space
// (frame_blocks.glsl): world axes, origin at the eye.
#ifndef HS_SURFACE_GLSL
#define HS_SURFACE_GLSL

// Lighting models a material chooses (scene materials: `model`).
const int MODEL_PBR = 0;          // GGX microfacet + energy-conserving diffuse (the default)
const int MODEL_LAMBERT = 1;      // diffuse only
const int MODEL_PHONG = 2;        // Lambert + Phong specular (reflection vector)
const int MODEL_BLINN_PHONG = 3;  // Lambert + Blinn-Phong specular (half vector)

struct Surface {
  vec3 position;   // eye space
  vec3 normal;     // unit, facing the viewer's side
  vec3 view;       // unit, towards the eye
  vec3 albedo;     // linear base colour
  float roughness; // 0..1 (perceptual)
  float metallic;  // 0..1
  float specular;  // Phong/Blinn-Phong: specular strength; PBR: dielectric F0 scale (0.5 = 4%)
  float shininess; // Phong/Blinn-Phong exponent
  vec3 emission;   // linear, added unlit
  float transmission;  // share of the diffuse light let through from the other side (brdf.glsl); 0: opaque
  int model;
};

#endif
