#version 450 core
// Layered depth of field, step 1 (docs/rendering.md "Depth of field";
// after Schedl & Wimmer 2012): one pixel's fragments from the A-buffer
// (every surface, no depth test: the opaque ones behind the front too),
// sorted front to back, split into K layers by their circle of confusion,
// each layer composited front to back within itself into a premultiplied
// colour and coverage (its matte), with the coverage-weighted mean signed
// CoC. The blur and the front-to-back composite of the layers follow in
// dof_composite.frag.
//
// Surfaces the capture does not draw (terrains, the sky) come from the
// opaque image (before the transparency passes: the capture has the
// translucent surfaces and particles): its front surface joins the list at its depth when no
// captured fragment is there (the sky at infinity). Where the front
// fragment is the list's first, its colour is taken from the opaque image
// (with ambient occlusion and MSAA), so the in-focus image is the pinhole one.
layout(local_size_x = 8, local_size_y = 8) in;

#define ABUFFER_MAX_FRAGMENTS 32
#include "abuffer_read.glsl"
#include "dof_common.glsl"

layout(binding = 24) uniform sampler2D uOpaqueColor;
layout(binding = 25) uniform sampler2D uOpaqueDepth;
layout(binding = 4, rgba16f) writeonly uniform image2DArray uLayerColor;
layout(binding = 5, r16f) writeonly uniform image2DArray uLayerCoc;
uniform int uLayers;     // K, 2..16
uniform vec2 uCocRange;  // signed CoC radius at the nearest drawn depth and at infinity

vec4 layerColor[16];
float layerCoc[16];

int layerOf(float coc) {
  float t = (coc - uCocRange.x) / max(uCocRange.y - uCocRange.x, 1e-6);
  return clamp(int(floor(t * float(uLayers))), 0, uLayers - 1);
}

void addFragment(vec4 c, float depth) {
  float coc = dofCocRadius(depth);
  int k = layerOf(coc);
  if (c.a < 0.0) {
    // Additive (oit_composite.glsl: a particle's light): it adds its
    // colour, dimmed by what lies before it in the layer, and covers nothing.
    layerColor[k].rgb += (1.0 - layerColor[k].a) * c.rgb;
    return;
  }
  float t = (1.0 - layerColor[k].a) * clamp(c.a, 0.0, 1.0);
  layerColor[k] += vec4(c.rgb * t, t);
  layerCoc[k] += coc * t;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uOpaqueDepth, 0);
  if (any(greaterThanEqual(p, size))) return;
  for (int k = 0; k < uLayers; ++k) {
    layerColor[k] = vec4(0.0);
    layerCoc[k] = 0.0;
  }
  float frontDepth = texelFetch(uOpaqueDepth, p, 0).r;
  vec3 frontColor = texelFetch(uOpaqueColor, p, 0).rgb;
  uint total;
  uint n = abufferLoadSorted(p, total);
  bool frontAdded = false;
  for (uint i = 0u; i < n; ++i) {
    uvec4 f = abufferFragments[i];
    float d = abufferDepth(f);
    vec4 c = abufferColor(f);
    bool isFront = abs(d - frontDepth) <= 1e-5 * frontDepth;
    if (!frontAdded && frontDepth > d && !isFront) {  // the opaque front lies before this fragment
      addFragment(vec4(frontColor, 1.0), frontDepth);
      frontAdded = true;
    }
    if (isFront && !frontAdded) {
      if (i == 0u) c.rgb = frontColor;
      frontAdded = true;
    }
    addFragment(c, d);
  }
  if (!frontAdded) addFragment(vec4(frontColor, 1.0), frontDepth);  // terrain or sky behind everything
  for (int k = 0; k < uLayers; ++k) {
    float a = layerColor[k].a;
    // An empty layer's CoC is its interval's middle (dof_composite.frag
    // weighs empty pixels by it).
    float mid = mix(uCocRange.x, uCocRange.y, (float(k) + 0.5) / float(uLayers));
    imageStore(uLayerColor, ivec3(p, k), layerColor[k]);
    imageStore(uLayerCoc, ivec3(p, k), vec4(a > 1e-4 ? layerCoc[k] / a : mid));
  }
}
