#version 450 core
// HDR linear scene -> display (docs/rendering.md "Post-processing"): the
// post chain's per-pixel effects in one pass, in the chain's order:
// exposure, bloom (added from the bloom chain's last upsample), chromatic
// aberration (on the scene's light), the tone map, the colour grade, the
// LUT, the vignette, film grain, then sRGB encoding (done here, so any 8-bit
// target, the Qt widget's included, shows correct sRGB). Each effect is a
// define, set only when enabled: with none the pass is exposure, the tone
// map and the encoding alone. When FXAA follows, luma goes to alpha for
// it; otherwise alpha is 1 (frames are opaque). tests/common/
// post_reference.h is the same arithmetic on the CPU, in double, what the
// tests hold this against.
#include "common.glsl"
#include "frame_blocks.glsl"
in vec2 vUv;
layout(binding = 0) uniform sampler2D uScene;
layout(binding = 1) uniform sampler2D uBloom;  // HS_BLOOM
uniform float uExposure;
uniform bool uLumaInAlpha;
uniform float uBloomIntensity;  // over the chain's weight sum
uniform float uCaScale;         // HS_CA: red scaled by 1 + k about the centre, blue by 1 - k
uniform vec3 uWhiteBalance;     // HS_GRADE
uniform vec3 uLift, uGamma, uGain;
uniform float uSaturation;
uniform float uVignette;        // HS_VIGNETTE
uniform vec2 uAspect;           // (width / height, 1) / its length: the corner at distance 1
uniform float uGrain;           // HS_GRAIN
uniform float uGrainCell;       // pixels per grain cell
uniform float uLutIntensity;    // HS_LUT: OpenColorIO's hsLut (render/color_lut.h), mixed in by this
                                // HS_VIEW_TRANSFORM: OpenColorIO's hsView replaces the tone curve
layout(location = 0) out vec4 outColor;

vec3 acesFitted(vec3 x) {
  // Narkowicz 2015 fit of the ACES RRT+ODT.
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// AgX (Sobotka), the published Rec.709 base: inset matrix, log2 encoding
// over [-12.47393, 4.026069] EV, the sigmoid as the 6th-order polynomial
// fit, outset matrix, then the 2.2 power back to display-linear.
vec3 agx(vec3 c) {
  const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                          0.0784335999999992, 0.878468636469772, 0.0784336,
                          0.0792237451477643, 0.0791661274605434, 0.879142973793104);
  const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                           -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                           -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
  const float minEv = -12.47393, maxEv = 4.026069;
  vec3 x = inset * max(c, vec3(0.0));
  x = clamp(log2(max(x, vec3(1e-10))), minEv, maxEv);
  x = (x - minEv) / (maxEv - minEv);
  const vec3 x2 = x * x, x4 = x2 * x2;
  x = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
  x = outset * x;
  return pow(clamp(x, 0.0, 1.0), vec3(2.2));
}

// Khronos PBR Neutral (2024): an offset for the darks, highlights above
// 0.76 compressed towards 1 and desaturated by how much they were.
vec3 pbrNeutral(vec3 c) {
  const float start = 0.8 - 0.04, desaturation = 0.15;
  const float x = min(c.r, min(c.g, c.b));
  const float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  c -= offset;
  const float peak = max(c.r, max(c.g, c.b));
  if (peak < start) return c;
  const float d = 1.0 - start;
  const float newPeak = 1.0 - d * d / (peak + d - start);
  c *= newPeak / peak;
  const float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return mix(c, vec3(newPeak), g);
}

// A value in [-1, 1) per grain cell and frame number (lowbias32, as
// particles/rng.h): the same in both eyes, screen-fixed as on a film print.
#include "lowbias32.glsl"
float grainAt(vec2 pixel) {
  const uvec2 cell = uvec2(floor(pixel / uGrainCell));
  const uint frameNumber = uint(frame.time.y);  // the FrameBlock's: a pure function of the timeline
  const uint h = lowbias32(lowbias32(lowbias32(frameNumber) ^ cell.x) ^ (cell.y * 0x9e3779b9U));
  return float(h >> 8) * (2.0 / 16777216.0) - 1.0;
}

void main() {
  vec3 c = texture(uScene, vUv).rgb;
#ifdef HS_CA
  // Lateral colour: red imaged a little larger, blue a little smaller.
  const vec2 fromCentre = vUv - 0.5;
  c.r = texture(uScene, 0.5 + fromCentre * (1.0 + uCaScale)).r;
  c.b = texture(uScene, 0.5 + fromCentre * (1.0 - uCaScale)).b;
#endif
  c *= uExposure;
#ifdef HS_BLOOM
  c += uBloomIntensity * texture(uBloom, vUv).rgb;
#endif
#if defined(HS_VIEW_TRANSFORM)
  // OpenColorIO's display/view transform (render/color_lut.h) in the tone
  // curve's place: scene-linear light in, display code values out, decoded
  // to display-linear for the grade and the rest (encoded again below, so
  // with nothing between the output is the transform's code values).
  c = srgbToLinear(clamp(hsView(vec4(c, 1.0)).rgb, 0.0, 1.0));
#elif defined(HS_TONEMAP_ACES)
  c = acesFitted(c);
#elif defined(HS_TONEMAP_AGX)
  c = agx(c);
#elif defined(HS_TONEMAP_NEUTRAL)
  c = clamp(pbrNeutral(c), 0.0, 1.0);
#endif
#ifdef HS_GRADE
  c *= uWhiteBalance;
  c = clamp(uGain * c + uLift * (1.0 - c), 0.0, 1.0);
  c = pow(c, 1.0 / uGamma);
  const float luma = dot(c, vec3(0.2126, 0.7152, 0.0722));
  c = max(mix(vec3(luma), c, uSaturation), 0.0);
#endif
#ifdef HS_LUT
  // A grading LUT maps display code values (what .cube looks are made
  // for): encoded to sRGB, looked up, decoded back to display-linear.
  const vec3 encoded = linearToSrgb(c);
  const vec3 looked = hsLut(vec4(encoded, 1.0)).rgb;
  c = srgbToLinear(clamp(mix(encoded, looked, uLutIntensity), 0.0, 1.0));
#endif
#ifdef HS_VIGNETTE
  // cos^4 of the angle a pinhole sees the corner at, scaled to the
  // intensity: 1 - intensity at the corner (r = 1), 1 at the centre.
  const float r = length((vUv - 0.5) * 2.0 * uAspect);
  const float falloff = 1.0 / ((1.0 + r * r) * (1.0 + r * r));  // cos^4 with the corner at 45 degrees
  c *= mix(1.0, (falloff - 0.25) / 0.75, uVignette);
#endif
#ifdef HS_GRAIN
  // Multiplicative luminance noise, fading out towards white (black stays black).
  const float l = clamp(dot(c, vec3(0.2126, 0.7152, 0.0722)), 0.0, 1.0);
  c *= 1.0 + uGrain * grainAt(gl_FragCoord.xy) * 4.0 * (1.0 - l);
#endif
  vec3 s = linearToSrgb(c);
  outColor = vec4(s, uLumaInAlpha ? dot(s, vec3(0.299, 0.587, 0.114)) : 1.0);
}
