#version 450 core
// The per-pixel stylised effects in one pass (render/passes/stylised_passes.h),
// on the display-encoded image, each compiled in only when enabled, in this
// order: the CRT's curved screen chooses where the pixel reads from
// (HS_CRT); the comic look posterises, draws halftone dots in the shadows
// and outlines (HS_COMIC), or outlines alone (HS_OUTLINES); the CRT's
// scanlines and mask; dithering to a few levels with an ordered Bayer
// (HS_DITHER_BAYER) or blue-noise (HS_DITHER_BLUE) threshold. Sizes in
// pixels are per 1080 rows. tests/common/stylised_reference.h is this
// file's CPU twin: a change here is a change there.
layout(binding = 0) uniform sampler2D uImage;
layout(binding = 1) uniform sampler2D uBlueNoise;  // (rank + 0.5) / count, tiled
uniform float uLines;            // rows / 1080
uniform float uLevels;           // comic: levels per channel
uniform float uDotCell;          // comic: halftone cell, pixels
uniform float uOutlineThreshold;
uniform vec3 uOutlineColor;      // display-encoded
uniform float uCurvature;
uniform float uScanlines;
uniform float uScanCount;        // scanlines over the height
uniform float uMask;
uniform float uDitherLevels;
layout(location = 0) out vec4 outColor;

vec2 gSize;

vec3 at(vec2 px) {
#ifdef HS_CRT
  return texture(uImage, px / gSize).rgb;  // between pixels on the curved screen
#else
  return texelFetch(uImage, clamp(ivec2(px), ivec2(0), ivec2(gSize) - 1), 0).rgb;
#endif
}

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The Sobel gradient of the luminance around `px`, over 4: a step of 0.25
// between neighbours reads 0.25.
float sobel(vec2 px) {
  const float tl = luma(at(px + vec2(-1, 1))), t = luma(at(px + vec2(0, 1))), tr = luma(at(px + vec2(1, 1)));
  const float l = luma(at(px + vec2(-1, 0))), r = luma(at(px + vec2(1, 0)));
  const float bl = luma(at(px + vec2(-1, -1))), b = luma(at(px + vec2(0, -1))), br = luma(at(px + vec2(1, -1)));
  const float gx = (tr + 2.0 * r + br) - (tl + 2.0 * l + bl);
  const float gy = (tl + 2.0 * t + tr) - (bl + 2.0 * b + br);
  return length(vec2(gx, gy)) * 0.25;
}

vec3 outline(vec3 c, vec2 px) {
  const float g = sobel(px);
  return mix(c, uOutlineColor, smoothstep(uOutlineThreshold, 1.5 * uOutlineThreshold, g));
}

float bayer8(ivec2 p) {
  // The 8x8 Bayer index from the bits of x and y interleaved (x ^ y and y).
  const int x = p.x & 7, y = p.y & 7;
  const int v = x ^ y;
  const int i = ((v & 1) << 5) | ((y & 1) << 4) | ((v & 2) << 2) | ((y & 2) << 1) | ((v & 4) >> 1) | ((y & 4) >> 2);
  return (float(i) + 0.5) / 64.0;
}

void main() {
  gSize = vec2(textureSize(uImage, 0));
  const ivec2 ip = ivec2(gl_FragCoord.xy);
  vec2 px = gl_FragCoord.xy;
#ifdef HS_CRT
  // The barrel: a point at distance r (of the half-diagonal's square,
  // corner = 2) from the centre reads from r * (1 + curvature r).
  vec2 c2 = px / gSize * 2.0 - 1.0;
  c2 *= 1.0 + uCurvature * dot(c2, c2);
  px = (c2 * 0.5 + 0.5) * gSize;
  const bool off = any(lessThan(c2, vec2(-1.0))) || any(greaterThan(c2, vec2(1.0)));
#endif
  vec3 c = at(px);
#if defined(HS_COMIC)
  const float levels = max(uLevels, 2.0) - 1.0;
  const float shade = luma(c);
  c = floor(c * levels + 0.5) / levels;
  // Halftone: a grid turned 45 degrees, a dot per cell growing with the
  // darkness below 60 % luminance, anti-aliased over a pixel.
  const vec2 r = mat2(0.70710678, 0.70710678, -0.70710678, 0.70710678) * gl_FragCoord.xy / uDotCell;
  const float d = length(fract(r) - 0.5);
  const float dark = clamp((0.6 - shade) / 0.6, 0.0, 1.0);
  const float radius = 0.7071 * sqrt(dark);
  const float ink = 1.0 - smoothstep(radius - 0.5 / uDotCell, radius + 0.5 / uDotCell, d);
  c *= 1.0 - 0.75 * ink * step(1e-4, dark);
  c = outline(c, px);
#elif defined(HS_OUTLINES)
  c = outline(c, px);
#endif
#ifdef HS_CRT
  // Scanlines: bright at each line's middle, dark between; an aperture
  // grille of red, green and blue columns.
  const float row = px.y / gSize.y * uScanCount;
  const float beam = 0.5 - 0.5 * cos(6.28318531 * row);
  c *= 1.0 - uScanlines * (1.0 - beam);
  vec3 mask = vec3(1.0 - uMask);
  mask[ip.x % 3] = 1.0;
  c *= mask;
  if (off) c = vec3(0.0);
#endif
#if defined(HS_DITHER_BAYER) || defined(HS_DITHER_BLUE)
#ifdef HS_DITHER_BAYER
  const float threshold = bayer8(ip);
#else
  const float threshold = texelFetch(uBlueNoise, ip % textureSize(uBlueNoise, 0), 0).r;
#endif
  const float steps = max(uDitherLevels, 2.0) - 1.0;
  c = min(floor(clamp(c, 0.0, 1.0) * steps + threshold), steps) / steps;
#endif
  outColor = vec4(c, 1.0);
}
