#version 450 core
// Layered depth of field, step 2 (dof_layers.comp made the layers): each
// layer's premultiplied colour and matte blurred by its own CoC (scatter as
// gather within the layer: a tap adds where its disc reaches this pixel,
// spread over its area; an empty pixel weighs in with its layer's CoC but
// adds nothing, so the matte's edge softens), then the layers composited
// front to back: a blurred near edge lets the layers behind show through
// (partial occlusion). What no layer covers after that (the sky or a
// terrain hidden behind a mesh, which the capture never saw) takes the
// blurred layers' own colour there, normalised.
in vec2 vUv;
layout(binding = 26) uniform sampler2DArray uLayerColor;
layout(binding = 27) uniform sampler2DArray uLayerCoc;
layout(location = 0) out vec4 outColor;

#include "dof_common.glsl"

uniform int uLayers;
uniform vec2 uCocRange;  // as in dof_layers.comp

const int kTaps = 64;

vec4 blurredLayer(ivec2 p, int k, ivec2 size) {
  vec4 centre = texelFetch(uLayerColor, ivec3(p, k), 0);
  float lo = mix(uCocRange.x, uCocRange.y, float(k) / float(uLayers));
  float hi = mix(uCocRange.x, uCocRange.y, float(k + 1) / float(uLayers));
  float radius = min(max(abs(lo), abs(hi)), uMaxRadius);
  if (radius < 0.5) return centre;
  float r0 = abs(texelFetch(uLayerCoc, ivec3(p, k), 0).r);
  float tapArea = 3.14159265 * radius * radius / float(kTaps);
  float w0 = 1.0 / max(r0 * r0, 0.25);
  vec4 sum = centre * w0;
  float weight = w0;
  for (int i = 0; i < kTaps; ++i) {
    vec2 o = dofTap(i, kTaps, radius);
    ivec2 q = clamp(p + ivec2(round(o)), ivec2(0), size - 1);
    float r = abs(texelFetch(uLayerCoc, ivec3(q, k), 0).r);
    float w = tapArea * dofCover(r, length(o)) / max(r * r, 0.25);
    sum += texelFetch(uLayerColor, ivec3(q, k), 0) * w;
    weight += w;
  }
  return sum / weight;
}

void main() {
  ivec2 size = textureSize(uLayerColor, 0).xy;
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 colour = vec3(0.0);
  float transmit = 1.0;
  vec4 all = vec4(0.0);
  for (int k = 0; k < uLayers; ++k) {
    vec4 l = blurredLayer(p, k, size);
    colour += transmit * l.rgb;
    transmit *= 1.0 - clamp(l.a, 0.0, 1.0);
    all += l;
  }
  if (transmit > 0.0 && all.a > 1e-4) colour += transmit * all.rgb / all.a;
  outColor = vec4(colour, 1.0);
}
