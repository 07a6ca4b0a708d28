#version 450 core
// Gather depth of field on the opaque HDR colour and depth (docs/rendering.md
// "Depth of field"): the cheap single-layer comparison for the layered pass.
// Scatter as gather: each tap on a disc of the largest CoC radius around
// this pixel (dof_tiles.frag) adds its colour where its own CoC disc reaches this pixel, spread over its
// disc's area (weight 1 / r^2), normalised. Near/far: a tap behind this
// pixel may spread no further than this pixel's own CoC (an in-focus
// foreground keeps its edge); a tap in front spreads freely over what lies
// behind it. What a single layer cannot do is show the background behind a
// blurred foreground edge (it was never drawn): the layered pass can.
in vec2 vUv;
layout(binding = 24) uniform sampler2D uColor;
layout(binding = 25) uniform sampler2D uDepth;
layout(binding = 26) uniform sampler2D uTiles;  // dof_tiles.frag
layout(location = 0) out vec4 outColor;

#include "dof_common.glsl"

const int kTaps = 64;

void main() {
  ivec2 size = textureSize(uColor, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 centre = texelFetch(uColor, p, 0);
  float d0 = texelFetch(uDepth, p, 0).r;
  float r0 = abs(dofCocRadius(d0));
  float radius = dofNeighbourhoodRadius(uTiles, p);
  if (radius < 0.5) {  // nothing around blurs this pixel
    outColor = centre;
    return;
  }
  // One tap stands for the disc's area / kTaps pixels; the centre for one.
  float tapArea = 3.14159265 * radius * radius / float(kTaps);
  float w0 = 1.0 / max(r0 * r0, 0.25);
  vec3 sum = centre.rgb * w0;
  float weight = w0;
  for (int i = 0; i < kTaps; ++i) {
    vec2 o = dofTap(i, kTaps, radius);
    ivec2 q = clamp(p + ivec2(round(o)), ivec2(0), size - 1);
    float d = texelFetch(uDepth, q, 0).r;
    float r = abs(dofCocRadius(d));
    if (d < d0) r = min(r, r0);  // behind this pixel (reversed-Z): no further than this pixel's blur
    float w = tapArea * dofCover(r, length(o)) / max(r * r, 0.25);
    sum += texelFetch(uColor, q, 0).rgb * w;
    weight += w;
  }
  outColor = vec4(sum / weight, centre.a);
}
