// A material's Surface (surface.glsl) at a point: what both the per-pixel
// (mesh.frag) and the per-vertex (mesh.vert, Gouraud) paths light.
#ifndef HS_MATERIAL_SURFACE_GLSL
#define HS_MATERIAL_SURFACE_GLSL
#include "material_block.glsl"
#include "surface.glsl"

Surface materialSurface(Material m, vec3 albedo, vec3 p, vec3 n) {
  Surface s;
  s.position = p;
  s.normal = n;
  s.view = normalize(-p);
  s.albedo = albedo;
  s.roughness = m.surface.x;
  s.metallic = m.surface.y;
  s.specular = m.surface.z;
  s.shininess = m.surface.w;
  s.emission = m.emission.rgb;
  s.transmission = m.detail.z;
  s.model = int(m.kind.x);
  return s;
}

#endif
