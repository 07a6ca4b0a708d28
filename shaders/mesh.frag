#version 450 core
// Meshes with their material (material_block.glsl): base colour x texture
// x instance tint, alpha cut-out, unlit or lit by lighting.glsl with the
// material's model. Shading variants from this one source:
//   (none)           Phong shading: lighting per pixel with the interpolated normal
//   SHADING_GOURAUD  lighting per vertex (mesh.vert), interpolated
//   SHADING_FLAT     the triangle's own normal (from screen derivatives), per pixel
// and surface detail (surface_detail.glsl), not with Gouraud:
//   HAS_NORMAL_MAP   tangent-space normal map
//   HAS_PARALLAX     parallax occlusion mapping from the height map
// DEBUG_SHADING_NORMAL writes the shading normal (world axes) instead of a colour.
// INSTANCED (an instanced source's instances): no tint, and the fade's
// dithered discard (instance_fade.glsl) next to the cut-out's.
#include "lighting.glsl"
#include "material_surface.glsl"
#include "mesh_uv.glsl"
#if defined(HAS_NORMAL_MAP) || defined(HAS_PARALLAX)
#include "surface_detail.glsl"
in vec4 vTangent;
#endif
#ifdef HS_OIT
#include "oit_output.glsl"
#endif
#ifdef INSTANCED
#include "instance_fade.glsl"
#endif

in vec3 vEyePos;
in vec3 vNormal;
in vec2 vUv;
flat in uint vObject;
#ifdef SHADING_GOURAUD
in vec3 vLit;
#endif

layout(location = 0) out vec4 outColor;

void main() {
  Material m = materials[uMaterial];
  vec2 uv = meshUv(vUv);  // held to the submesh's UV range (mesh_uv.glsl)
#ifndef SHADING_GOURAUD
#ifdef SHADING_FLAT
  vec3 n = normalize(cross(dFdx(vEyePos), dFdy(vEyePos)));
  if (dot(n, vNormal) < 0.0) n = -n;
#else
  vec3 n = normalize(vNormal);
#endif
  // Two-sided materials light the side the eye sees (one-sided ones are culled).
  if (!gl_FrontFacing) n = -n;
#if defined(HAS_NORMAL_MAP) || defined(HAS_PARALLAX)
  TangentFrame frame = tangentFrame(n, vTangent);
#endif
#ifdef HAS_PARALLAX
  vec3 toEye = normalize(-vEyePos);
  vec3 v = vec3(dot(toEye, frame.t), dot(toEye, frame.up), dot(toEye, frame.n));
  uv = parallaxUv(uv, v, m.detail.y * uvPerMetre(uv, vEyePos));
#endif
#ifdef HAS_NORMAL_MAP
  n = normalFromMap(frame, texture(uNormalMap, uv).rgb, m.detail.x);
#endif
#endif
  vec4 texel = hasFlag(m, MAT_BASE_TEXTURE) ? texture(uBaseColorTexture, uv) : vec4(1.0);
#ifdef INSTANCED
  vec3 tint = vec3(1.0);  // vObject is an instance id (mesh.vert)
#else
  vec3 tint = objects[vObject].tint.rgb;
#endif
  vec4 base = vec4(m.baseColor.rgb * tint, m.baseColor.a) * texel;
  if (hasFlag(m, MAT_ALPHA_CUTOUT) && base.a < m.emission.a) discard;
#ifdef INSTANCED
  // After the texture reads (their derivatives), as the cut-out is.
  instanceFadeDiscard();
#endif
#ifdef SHADING_GOURAUD
  outColor = vec4(vLit * texel.rgb, 0.0);  // alpha: no ambient share to occlude (per-vertex light)
#else
#ifdef DEBUG_SHADING_NORMAL
  outColor = vec4(n, 1.0);
  return;
#endif
  if (hasFlag(m, MAT_UNLIT)) {
    outColor = vec4(applyFog(base.rgb + m.emission.rgb, vEyePos), 0.0);  // alpha: nothing ambient
    return;
  }
  outColor = vec4(shadeSurface(materialSurface(m, base.rgb, vEyePos, n)), hsAmbientShare);
#endif
}
#ifdef HS_OIT
#include "oit_main.glsl"
#endif
