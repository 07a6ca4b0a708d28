// The tail: fragments that found no place in the A-buffer's pool, the
// fixed array or the K-buffer's slots are not dropped but summed per pixel
// (buffer 14, two uvec4 per pixel) in fixed point with integer atomics, so
// the sums do not depend on the order fragments arrive in (float atomics
// would round differently each run). The resolve composites the tail
// behind the stored fragments as one layer: its colour is the
// opacity-weighted mean, its opacity 1 - prod(1 - a) (from the sum of
// -log(1 - a)). Sums are in 1/4096 units; a colour x opacity over
// OIT_TAIL_MAX_COLOR is clamped, so 16 000 fragments of a pixel fit in 32 bits.
#ifndef HS_OIT_TAIL_GLSL
#define HS_OIT_TAIL_GLSL

#define OIT_TAIL_SCALE 4096.0
#define OIT_TAIL_MAX_COLOR 64.0

// [2i]: sum a*r, a*g, a*b, a; [2i+1]: sum -log(1 - a), count, unused x2.
layout(std430, binding = 14) coherent buffer OitTail { uvec4 oitTail[]; };

void oitTailAdd(uint pixelIndex, vec4 c) {
  // An additive layer (oit_composite.glsl) cannot join an opacity-weighted
  // mean: it is dropped (already counted as overflow).
  if (c.a < 0.0) return;
  const float a = clamp(c.a, 0.0, 0.999);
  const uvec3 rgb = uvec3(clamp(c.rgb * a, 0.0, OIT_TAIL_MAX_COLOR) * OIT_TAIL_SCALE + 0.5);
  atomicAdd(oitTail[2u * pixelIndex].x, rgb.r);
  atomicAdd(oitTail[2u * pixelIndex].y, rgb.g);
  atomicAdd(oitTail[2u * pixelIndex].z, rgb.b);
  atomicAdd(oitTail[2u * pixelIndex].w, uint(a * OIT_TAIL_SCALE + 0.5));
  atomicAdd(oitTail[2u * pixelIndex + 1u].x, uint(-log(1.0 - a) * OIT_TAIL_SCALE + 0.5));
  atomicAdd(oitTail[2u * pixelIndex + 1u].y, 1u);
}

// The pixel's tail as one straight colour and opacity (opacity 0: none).
vec4 oitTailLayer(uint pixelIndex) {
  const uvec4 s = oitTail[2u * pixelIndex];
  const uvec4 t = oitTail[2u * pixelIndex + 1u];
  if (t.y == 0u || s.w == 0u) return vec4(0.0);
  return vec4(vec3(s.xyz) / float(s.w), 1.0 - exp(-float(t.x) / OIT_TAIL_SCALE));
}

#endif
