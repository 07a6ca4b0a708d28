// The tail: fragments that found no place in the A-buffer's pool, the
// fixed array or the K-buffer's slots are not dropped but summed per pixel
// (buffer 14, three uvec4 per pixel: render/abuffer.h kOitTailBytesPerPixel)
// in fixed point with integer atomics, so the sums do not depend on the
// order fragments arrive in (float atomics would round differently each
// run). The resolve composites the tail behind the stored fragments as
// one layer: its colour is the opacity-weighted mean, its opacity
// 1 - prod(1 - a) (from the sum of -log(1 - a)). Additive layers
// (oit_composite.glsl: particles' light) are summed apart: light adds in
// any order, so their sum is exact; the resolve adds it in front of the
// tail's layer (where among the tail's fragments each lay is not kept).
// Sums are in 1/4096 units; a colour (x opacity) over OIT_TAIL_MAX_COLOR
// is clamped, so 16 000 fragments of a pixel fit in 32 bits.
#ifndef HS_OIT_TAIL_GLSL
#define HS_OIT_TAIL_GLSL

#define OIT_TAIL_SCALE 4096.0
#define OIT_TAIL_MAX_COLOR 64.0

// [3i]: sum a*r, a*g, a*b, a; [3i+1]: sum -log(1 - a), count, unused x2;
// [3i+2]: the additive layers' light r, g, b, unused.
layout(std430, binding = 14) coherent buffer OitTail { uvec4 oitTail[]; };

void oitTailAdd(uint pixelIndex, vec4 c) {
  const uint i = 3u * pixelIndex;
  if (c.a < 0.0) {
    const uvec3 light = uvec3(clamp(c.rgb, 0.0, OIT_TAIL_MAX_COLOR) * OIT_TAIL_SCALE + 0.5);
    atomicAdd(oitTail[i + 2u].x, light.r);
    atomicAdd(oitTail[i + 2u].y, light.g);
    atomicAdd(oitTail[i + 2u].z, light.b);
    return;
  }
  const float a = clamp(c.a, 0.0, 0.999);
  const uvec3 rgb = uvec3(clamp(c.rgb * a, 0.0, OIT_TAIL_MAX_COLOR) * OIT_TAIL_SCALE + 0.5);
  atomicAdd(oitTail[i].x, rgb.r);
  atomicAdd(oitTail[i].y, rgb.g);
  atomicAdd(oitTail[i].z, rgb.b);
  atomicAdd(oitTail[i].w, uint(a * OIT_TAIL_SCALE + 0.5));
  atomicAdd(oitTail[i + 1u].x, uint(-log(1.0 - a) * OIT_TAIL_SCALE + 0.5));
  atomicAdd(oitTail[i + 1u].y, 1u);
}

// The pixel's tail as one straight colour and opacity (opacity 0: none).
vec4 oitTailLayer(uint pixelIndex) {
  const uvec4 s = oitTail[3u * pixelIndex];
  const uvec4 t = oitTail[3u * pixelIndex + 1u];
  if (t.y == 0u || s.w == 0u) return vec4(0.0);
  return vec4(vec3(s.xyz) / float(s.w), 1.0 - exp(-float(t.x) / OIT_TAIL_SCALE));
}

// The light of the pixel's additive layers in the tail (0: none).
vec3 oitTailLight(uint pixelIndex) { return vec3(oitTail[3u * pixelIndex + 2u].xyz) / OIT_TAIL_SCALE; }

#endif
