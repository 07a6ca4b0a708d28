#version 450 core
// SMAA, pass 1 of 3 (render/passes/smaa_passes.h): luma edges of the
// tone-mapped picture. r: an edge on the pixel's left side (between x-1 and
// x), g: on its top side (between y and y+1, GL rows grow upwards). An
// edge is a luma step of at least uThreshold that is not much weaker than
// the strongest step next to it (SMAA's local contrast adaptation, factor
// 2): a weak edge beside a strong one is no edge of its own.
layout(binding = 0) uniform sampler2D uImage;
uniform float uThreshold;
layout(location = 0) out vec4 outEdges;

const vec3 kLuma = vec3(0.2126, 0.7152, 0.0722);

float lumaAt(ivec2 p) {
  return dot(texelFetch(uImage, clamp(p, ivec2(0), textureSize(uImage, 0) - 1), 0).rgb, kLuma);
}

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const float l = lumaAt(p);
  const vec2 near = vec2(lumaAt(p + ivec2(-1, 0)), lumaAt(p + ivec2(0, 1)));
  const vec2 delta = abs(l - near);
  vec2 edges = step(uThreshold, delta);
  // No edge: nothing written (the target starts at 0) and, above all, no
  // depth: the weights pass runs only where this pass wrote its depth.
  if (edges.x + edges.y == 0.0) discard;
  const vec2 across = abs(l - vec2(lumaAt(p + ivec2(1, 0)), lumaAt(p + ivec2(0, -1))));
  const vec2 beyond = abs(near - vec2(lumaAt(p + ivec2(-2, 0)), lumaAt(p + ivec2(0, 2))));
  const vec2 strongest = max(max(delta, across), beyond);
  edges *= step(max(strongest.x, strongest.y), 2.0 * delta);
  if (edges.x + edges.y == 0.0) discard;
  outEdges = vec4(edges, 0.0, 0.0);
}
