// The end of mesh.frag's HS_OIT variants (oit_output.glsl renamed its main
// meshShade): shade, take the material's opacity, store the fragment.
#undef main

// The material's opacity x the base texture's alpha (mesh.frag's own
// `base.a`; parallax-shifted UVs are not followed here).
float oitOpacity() {
  Material m = materials[uMaterial];
  float a = m.baseColor.a;
  if (hasFlag(m, MAT_BASE_TEXTURE)) a *= texture(uBaseColorTexture, vUv).a;
  return clamp(a, 0.0, 1.0);
}


#if defined(HS_OIT_ABUFFER) || defined(HS_OIT_FIXED) || defined(HS_OIT_KBUFFER)
// What finds no place: counted, and summed into the tail where there is one.
void oitOverflow(vec4 c) {
  atomicAdd(abufferCounters.overflow, 1u);
#ifdef HS_OIT_TAIL
  oitTailAdd(abufferPixel(ivec2(gl_FragCoord.xy)), c);
#endif
}
#endif

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
#if defined(HS_OIT_ABUFFER)
  const uint i = atomicAdd(abufferCounters.allocated, 1u);
  if (i < abufferCounters.capacity) {
    uvec4 node = abufferPack(c, gl_FragCoord.z);
    // The link to the pixel's list is made by abuffer_link.comp: .w holds
    // the pixel until then (abuffer.glsl says why).
    node.w = abufferPixel(p);
    abufferNodes[i] = node;
  } else {
    oitOverflow(c);
  }
#elif defined(HS_OIT_FIXED)
  // oit_fixed_slots.frag gave the fragment a layer with its key, or none.
  const uint key = oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID));
  const uint n = min(oitFixedCount[abufferPixel(p)], uint(OIT_FIXED_LAYERS));
  for (int i = 0; i < OIT_FIXED_LAYERS; ++i) {
    if (uint(i) >= n) break;
    if (imageLoad(uOitFixedKeys, ivec3(p, i)).x == key) {
      uvec4 node = abufferPack(c, gl_FragCoord.z);
      node.w = key;
      imageStore(uOitFixedLayers, ivec3(p, i), node);
      return;
    }
  }
  oitOverflow(c);
#elif defined(HS_OIT_KBUFFER)
  const uint key = oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID));
  for (int i = 0; i < OIT_K; ++i) {
    const uint slot = imageLoad(uOitSlots, ivec3(p, i)).x;
    if (slot == key) {
      imageStore(uOitColors, ivec3(p, i), uvec4(packHalf2x16(c.rg), packHalf2x16(c.ba), 0u, 0u));
      return;
    }
    if (slot > key) break;
  }
  oitOverflow(c);
#elif defined(HS_OIT_WEIGHTED)
  // McGuire & Bavoil 2013, eq. 10: nearer layers weigh more (d in metres).
  const float d = length(vEyePos);
  const float w = c.a * clamp(10.0 / (1e-5 + pow(d / 5.0, 2.0) + pow(d / 200.0, 6.0)), 1e-2, 3e3);
  outColor = vec4(c.rgb * c.a, c.a) * w;
  oitRevealage = c.a;
#elif defined(HS_OIT_PEEL)
  outColor = c;
#endif
}
