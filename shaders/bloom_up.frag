#version 450 core
// Bloom's upsample (render/passes/bloom_passes.h): the dual filter's eight
// taps (a tent) over the coarser level, weighted by the radius, added to
// the downsampled level of this size.
in vec2 vUv;
layout(binding = 0) uniform sampler2D uCoarse;  // the level below, upsampled
layout(binding = 1) uniform sampler2D uLevel;   // this size's downsample
uniform vec2 uTexel;   // one texel of the coarse level
uniform float uRadius; // the coarse level's weight
layout(location = 0) out vec4 outColor;

void main() {
  const vec2 t = uTexel;
  vec3 sum = texture(uCoarse, vUv + vec2(-2.0 * t.x, 0.0)).rgb + texture(uCoarse, vUv + vec2(2.0 * t.x, 0.0)).rgb +
             texture(uCoarse, vUv + vec2(0.0, -2.0 * t.y)).rgb + texture(uCoarse, vUv + vec2(0.0, 2.0 * t.y)).rgb;
  sum += 2.0 * (texture(uCoarse, vUv + vec2(-t.x, -t.y)).rgb + texture(uCoarse, vUv + vec2(t.x, -t.y)).rgb +
                texture(uCoarse, vUv + vec2(-t.x, t.y)).rgb + texture(uCoarse, vUv + t).rgb);
  outColor = vec4(texture(uLevel, vUv).rgb + uRadius * sum / 12.0, 1.0);
}
