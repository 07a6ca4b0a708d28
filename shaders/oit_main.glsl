// The end of mesh.frag's HS_OIT variants (oit_output.glsl renamed its main
// meshShade): shade, take the material's opacity, store the fragment.
#undef main
#include "mesh_uv.glsl"

// The material's opacity x the base texture's alpha (mesh.frag's own
// `base.a`; parallax-shifted UVs are not followed here).
float oitOpacity() {
  Material m = materials[uMaterial];
  float a = m.baseColor.a;
  if (hasFlag(m, MAT_BASE_TEXTURE)) a *= texture(uBaseColorTexture, meshUv(vUv)).a;
  return clamp(a, 0.0, 1.0);
}


#if defined(HS_OIT_ABUFFER) || defined(HS_OIT_KBUFFER)
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
  // The key pass gave this fragment a node holding its depth and key, in
  // its pixel's sorted range (abuffer_keys.frag): find it by binary search
  // in the range's order. No node (over the cap, or a full tie whose twin
  // took it): the tail.
  const uint key = oitKey(gl_FragCoord.z, vObject, uint(gl_PrimitiveID));
  const uvec2 me = uvec2(floatBitsToUint(gl_FragCoord.z), key);
  const uint pixel = abufferPixel(p), begin = abufferStarts[pixel];
  const uint range = abufferStarts[pixel + 1u] - begin, count = imageLoad(uABufferCounts, p).x;
  const bool byKey = count > range;  // abufferByKey
  // The nodes in use: a fixed array's range past the pixel's fragments stays empty.
  const uint end = begin + min(count, range);
  uint lo = begin, hi = end;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    const uvec2 there = abufferNodes[mid].zw;
    if (byKey ? there.y < key : abufferNearer(there, me)) lo = mid + 1u;
    else hi = mid;
  }
  const uvec4 found = lo < end ? abufferNodes[lo] : uvec4(0u);
  if (lo < end && found.w == key && (byKey || found.z == me.x) && !abufferWritten(found))
    abufferNodes[lo] = abufferNode(c, gl_FragCoord.z, key);
  else
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
