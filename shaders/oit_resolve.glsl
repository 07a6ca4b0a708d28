// The transparency resolve (render/oit.cpp), one variant per mode, in
// oit_resolve.comp (OIT_COMPUTE: the A-buffer, fixed array and K-buffer,
// into an image) or oit_resolve.frag (the others, and the blend of that
// image over the opaque colour: OIT_RESOLVE_REFERENCE reads one): the
// pixel's translucent layers composited front to back (oit_composite.glsl),
// written as (colour, transmittance) and blended ONE, SRC_ALPHA over the
// opaque colour, so result = colour + transmittance x opaque.
//   OIT_RESOLVE_ABUFFER   the pixel's range of the A-buffer (and of the fixed
//                         array, which is one), in the order the capture sorted it
//   OIT_RESOLVE_KBUFFER   the K slots (already in order)
//   OIT_RESOLVE_WEIGHTED  weighted blended OIT's average colour and revealage
//   OIT_RESOLVE_REFERENCE the depth-peeling accumulation
//   OIT_PEEL_ACCUMULATE   (not a resolve) one peeled layer's premultiplied colour,
//                         blended under the accumulation
// Tails (OIT_RESOLVE_ABUFFER and _KBUFFER with uOitTail) come last, as
// one layer behind the stored ones; their share of each pixel is summed
// into the counters for --stats.
#include "oit_composite.glsl"
#if defined(OIT_RESOLVE_ABUFFER) || defined(OIT_RESOLVE_KBUFFER)
#include "abuffer.glsl"
#include "oit_tail.glsl"
#define OIT_HAS_TAIL
uniform bool uOitTail;
#endif
#ifdef OIT_RESOLVE_KBUFFER
#include "oit_kbuffer.glsl"
#endif
#ifdef OIT_RESOLVE_WEIGHTED
layout(binding = 20) uniform sampler2D uOitAccum;
layout(binding = 21) uniform sampler2D uOitRevealage;
#endif
#if defined(OIT_RESOLVE_REFERENCE) || defined(OIT_PEEL_ACCUMULATE)
layout(binding = 20) uniform sampler2D uOitLayer;  // the accumulation, or the peeled layer
#endif
#ifdef OIT_COMPUTE
// The sorting resolves run as compute: on llvmpipe a fragment shader's
// dynamically indexed private array (the sorted fragments) read back zero
// for some pixels of a 4x4 block when the block's pixels had lists of
// different lengths; a compute invocation per pixel reads what it wrote.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform writeonly image2D uOitResult;  // image unit 0: colour, transmittance
uniform ivec2 uOitSize;
#else
layout(location = 0) out vec4 outColor;
#endif

void main() {
#ifdef OIT_COMPUTE
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= uOitSize.x || p.y >= uOitSize.y) return;
#else
  const ivec2 p = ivec2(gl_FragCoord.xy);
#endif
#ifdef OIT_PEEL_ACCUMULATE
  const vec4 c = texelFetch(uOitLayer, p, 0);
  // An additive layer (opacity < 0, oit_composite.glsl) adds its colour and
  // leaves the transmittance.
  outColor = c.a < 0.0 ? vec4(c.rgb, 0.0) : vec4(c.rgb * c.a, c.a);
  return;
#endif
  OitComposite s = oitBegin();
#if defined(OIT_RESOLVE_ABUFFER)
  // The pixel's range, already sorted by the capture (abuffer_sort_keys.comp).
  const uint pixel = abufferPixel(p), end = abufferStarts[pixel + 1u];
  for (uint i = abufferStarts[pixel]; i < end; ++i) {
    const uvec4 f = abufferNodes[i];
    if (abufferWritten(f)) oitAdd(s, abufferColor(f));
  }
#elif defined(OIT_RESOLVE_KBUFFER)
  for (int i = 0; i < OIT_K; ++i) {
    if (imageLoad(uOitSlots, ivec3(p, i)).x == OIT_KEY_EMPTY) break;
    const uvec4 c = imageLoad(uOitColors, ivec3(p, i));
    oitAdd(s, vec4(unpackHalf2x16(c.x), unpackHalf2x16(c.y)));
  }
#elif defined(OIT_RESOLVE_WEIGHTED)
  const float r = texelFetch(uOitRevealage, p, 0).r;
  if (r >= 1.0) {
    outColor = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  const vec4 accum = texelFetch(uOitAccum, p, 0);
  s.color = accum.rgb / max(accum.a, 1e-5) * (1.0 - r);
  s.transmittance = r;
#elif defined(OIT_RESOLVE_REFERENCE)
  const vec4 a = texelFetch(uOitLayer, p, 0);
  s.color = a.rgb;
  s.transmittance = a.a;
#endif
#ifdef OIT_HAS_TAIL
  if (uOitTail) {
    // The tail's additive light, in front of its mean layer.
    s.color += s.transmittance * oitTailLight(abufferPixel(p));
    const vec4 t = oitTailLayer(abufferPixel(p));
    if (t.a > 0.0) {
      const float share = s.transmittance * t.a;
      oitAdd(s, t);
      atomicAdd(abufferCounters.tailShare, uint(share * 65536.0 + 0.5));
      atomicAdd(abufferCounters.tailPixels, 1u);
    }
  }
#endif
#ifdef OIT_COMPUTE
  imageStore(uOitResult, p, vec4(s.color, s.transmittance));
#else
  outColor = vec4(s.color, s.transmittance);
#endif
}
