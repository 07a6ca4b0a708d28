// The end of mesh.frag's HS_OIT variants (oit_output.glsl renamed its main
// meshShade): shade, take the material's opacity, store the fragment.
#undef main
#include "mesh_uv.glsl"

// The material's opacity x the base texture's alpha (mesh.frag's own
// `base.a`; parallax-shifted UVs are not followed here). A cut-out
// material is opaque where it is not cut (the layered depth of field
// captures it): its alpha only decides the cut, in mesh.frag.
float oitOpacity() {
  Material m = materials[uMaterial];
  if (hasFlag(m, MAT_ALPHA_CUTOUT)) return 1.0;
  float a = m.baseColor.a;
  if (hasFlag(m, MAT_BASE_TEXTURE)) a *= texture(uBaseColorTexture, meshUv(vUv)).a;
  return clamp(a, 0.0, 1.0);
}


#include "oit_store.glsl"

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
#ifdef HS_OIT_PEEL
  // Reversed Z: nearer is larger. Behind (or on) the opaque surface, or not
  // behind the layer peeled last: not this layer's.
  if (gl_FragCoord.z <= texelFetch(uOitOpaqueDepth, p, 0).r) discard;
  if (gl_FragCoord.z >= texelFetch(uOitPeeledDepth, p, 0).r) discard;
#endif
  meshShade();
  const vec4 c = vec4(outColor.rgb, oitOpacity());
  // A helper invocation (a pixel the triangle does not cover, run for the
  // derivatives of its neighbours) must store nothing (see abuffer.glsl on
  // why every atomic here is a buffer's).
  if (gl_HelperInvocation) return;
  oitStore(c, vObject, length(vEyePos));
}
