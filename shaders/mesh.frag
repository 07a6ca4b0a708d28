#version 450 core
// Meshes with their material (material_block.glsl): base colour x texture
// x instance tint, alpha cut-out, unlit or lit by lighting.glsl with the
// material's model. Shading variants from this one source:
//   (none)           Phong shading: lighting per pixel with the interpolated normal
//   SHADING_GOURAUD  lighting per vertex (mesh.vert), interpolated
//   SHADING_FLAT     the triangle's own normal (from screen derivatives), per pixel
#include "lighting.glsl"
#include "material_surface.glsl"

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
  vec2 uv = vUv;
  vec4 texel = hasFlag(m, MAT_BASE_TEXTURE) ? texture(uBaseColorTexture, uv) : vec4(1.0);
  vec4 base = vec4(m.baseColor.rgb * objects[vObject].tint.rgb, m.baseColor.a) * texel;
  if (hasFlag(m, MAT_ALPHA_CUTOUT) && base.a < m.emission.a) discard;
#ifdef SHADING_GOURAUD
  outColor = vec4(vLit * texel.rgb, base.a);
#else
  if (hasFlag(m, MAT_UNLIT)) {
    outColor = vec4(applyFog(base.rgb + m.emission.rgb, vEyePos), base.a);
    return;
  }
#ifdef SHADING_FLAT
  vec3 n = normalize(cross(dFdx(vEyePos), dFdy(vEyePos)));
  if (dot(n, vNormal) < 0.0) n = -n;
#else
  vec3 n = normalize(vNormal);
#endif
  // Two-sided materials light the side the eye sees (one-sided ones are culled).
  if (!gl_FrontFacing) n = -n;
  outColor = vec4(shadeSurface(materialSurface(m, base.rgb, vEyePos, n)), base.a);
#endif
}
