#version 450 core
// Bloom's downsample (render/passes/bloom_passes.h): the dual filter's
// five bilinear taps (the centre four times, four corners half a texel out)
// over the source, into a target half its size. The first level also
// exposes the scene's light and keeps what lies above the threshold
// (HS_BLOOM_PREFILTER: a quadratic soft knee over half the threshold).
in vec2 vUv;
layout(binding = 0) uniform sampler2D uSource;
uniform vec2 uTexel;        // one texel of the source
uniform float uExposure;    // HS_BLOOM_PREFILTER
uniform float uThreshold;
layout(location = 0) out vec4 outColor;

vec3 tap(vec2 uv) {
  vec3 c = texture(uSource, uv).rgb;
#ifdef HS_BLOOM_PREFILTER
  c *= uExposure;
  const float knee = 0.5 * uThreshold;
  const float bright = max(c.r, max(c.g, c.b));
  float soft = clamp(bright - uThreshold + knee, 0.0, 2.0 * knee);
  soft = knee > 0.0 ? soft * soft / (4.0 * knee) : 0.0;
  c *= max(soft, bright - uThreshold) / max(bright, 1e-4);
#endif
  return c;
}

void main() {
  const vec2 h = uTexel;  // half a target texel: one source texel
  vec3 sum = tap(vUv) * 4.0;
  sum += tap(vUv + vec2(-h.x, -h.y)) + tap(vUv + vec2(h.x, -h.y)) + tap(vUv + vec2(-h.x, h.y)) + tap(vUv + h);
  outColor = vec4(sum / 8.0, 1.0);
}
