// How a transparency variant stores one translucent fragment (render/oit.h):
// shared by mesh.frag's HS_OIT_* variants (oit_main.glsl) and the particle
// shader (particle.frag), so every kind of geometry lands in the A-buffer,
// the K-buffer, weighted OIT's targets or a peel the same way. `c` is the
// straight linear colour with its opacity (an opacity below 0 marks an
// additive layer, oit_composite.glsl); `object` goes into the sort key with
// gl_PrimitiveID; `eyeDistance` (metres) weighs weighted OIT's layers;
// `depth` is the fragment's (gl_FragCoord.z but where the shader computes
// its own, as impostor.frag does: the key pass used the same).
// Needs oit_output.glsl's declarations and the shader's outColor.
#ifndef HS_OIT_STORE_GLSL
#define HS_OIT_STORE_GLSL

#if defined(HS_OIT_ABUFFER) || defined(HS_OIT_KBUFFER)
// What finds no place: counted, and summed into the tail where there is one.
void oitOverflow(vec4 c) {
  atomicAdd(abufferCounters.overflow, 1u);
#ifdef HS_OIT_TAIL
  oitTailAdd(abufferPixel(ivec2(gl_FragCoord.xy)), c);
#endif
}
#endif

void oitStoreAt(vec4 c, uint object, float eyeDistance, float depth) {
  const ivec2 p = ivec2(gl_FragCoord.xy);
#if defined(HS_OIT_ABUFFER)
  // The key pass gave this fragment a node holding its depth and key, in
  // its pixel's sorted range (abuffer_keys.frag): find it by binary search
  // in the range's order. No node (over the cap, or a full tie whose twin
  // took it): the tail.
  const uint key = oitKey(depth, object, uint(gl_PrimitiveID));
  const uvec2 me = uvec2(floatBitsToUint(depth), key);
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
    abufferNodes[lo] = abufferNode(c, depth, key);
  else
    oitOverflow(c);
#elif defined(HS_OIT_KBUFFER)
  const uint key = oitKey(depth, object, uint(gl_PrimitiveID));
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
  // An additive layer has no place in weighted OIT's normalised average
  // (light without opacity would be divided by the layers' opacity): it is
  // blended as a layer of opacity min(1, its brightest channel) with the
  // colour that adds the same light (a x colour = its colour). It hides that
  // share of what lies behind it: weighted OIT's approximation of it.
  if (c.a < 0.0) {
    const float a = clamp(max(c.r, max(c.g, c.b)), 1e-3, 1.0);
    c = vec4(c.rgb / a, a);
  }
  // McGuire & Bavoil 2013, eq. 10: nearer layers weigh more (d in metres).
  const float d = eyeDistance;
  const float w = c.a * clamp(10.0 / (1e-5 + pow(d / 5.0, 2.0) + pow(d / 200.0, 6.0)), 1e-2, 3e3);
  outColor = vec4(c.rgb * c.a, c.a) * w;
  oitRevealage = c.a;
#elif defined(HS_OIT_PEEL)
  outColor = c;
#endif
}

void oitStore(vec4 c, uint object, float eyeDistance) { oitStoreAt(c, object, eyeDistance, gl_FragCoord.z); }

#endif
