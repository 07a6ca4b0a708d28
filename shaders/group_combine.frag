#version 450 core
// View groups combined (render/passes/group_combine.h), pixel for pixel in
// linear HDR. Without HS_PATTERN: the weighted sum of up to four groups'
// images (a crossfade, a dip to black). With HS_PATTERN (a
// sequencer::Transition's value): that stylised transition from image 0
// (outgoing) to image 1 (incoming) at uProgress, drawn as a pattern over
// the screen (docs/sequencer.md "Transitions"); each is a program of its
// own, since a software rasteriser runs every branch of a uniform switch.
// Every eye draws the same pattern at the same screen place.
// tests/common/transition_reference.h is this file's CPU twin: a change
// here is a change there.
layout(binding = 24) uniform sampler2D uImage0;
layout(binding = 25) uniform sampler2D uImage1;
layout(binding = 26) uniform sampler2D uImage2;
layout(binding = 27) uniform sampler2D uImage3;
uniform vec4 uWeights;
uniform int uImages;
uniform float uProgress;  // eased, 0..1
uniform uint uFrame;      // seeds the glitch
layout(location = 0) out vec4 outColor;

const float kPi = 3.14159265358979;

// The stylised transitions' patterns hash with lowbias32: the same bits on
// the GPU and in the CPU twin, so patterns that switch on it match exactly.
#include "lowbias32.glsl"
// In [0, 1), 24 bits: exact in a float.
float rand3(uint a, uint b, uint c) { return float(lowbias32(a ^ lowbias32(b ^ lowbias32(c))) >> 8) / 16777216.0; }

vec2 gSize;
vec4 at0(vec2 px) { return texture(uImage0, px / gSize); }  // bilinear, px in pixels (centres at +0.5)
vec4 at1(vec2 px) { return texture(uImage1, px / gSize); }
vec4 fetch0(ivec2 p) { return texelFetch(uImage0, clamp(p, ivec2(0), ivec2(gSize) - 1), 0); }
vec4 fetch1(ivec2 p) { return texelFetch(uImage1, clamp(p, ivec2(0), ivec2(gSize) - 1), 0); }

// The share of the incoming shot where an edge moving over 0..1 has reached
// `x`: fully in behind the edge, a soft band of +-soft around it.
float edge(float x, float p, float soft) {
  const float e = p * (1.0 + 2.0 * soft) - soft;
  return 1.0 - smoothstep(e - soft, e + soft, x);
}

vec4 weighted(ivec2 p) {
  vec4 sum = texelFetch(uImage0, p, 0) * uWeights.x;
  if (uImages > 1) sum += texelFetch(uImage1, p, 0) * uWeights.y;
  if (uImages > 2) sum += texelFetch(uImage2, p, 0) * uWeights.z;
  if (uImages > 3) sum += texelFetch(uImage3, p, 0) * uWeights.w;
  return sum;
}

void main() {
  const ivec2 ip = ivec2(gl_FragCoord.xy);
#ifndef HS_PATTERN
  outColor = weighted(ip);
#else
  gSize = vec2(textureSize(uImage0, 0));
  const vec2 px = gl_FragCoord.xy;
  const float lines = gSize.y / 1080.0;  // sizes in pixels are per 1080 rows
  const vec2 q = (px - 0.5 * gSize) / gSize.y;  // from the centre, in heights, y up
  const float p = uProgress;
  const float peak = sin(kPi * p);  // 0 at both ends, 1 in the middle
#if HS_PATTERN == 3  // crossfade_blur
  // A disc of 16 taps on a golden-angle spiral, its radius peaking mid-way.
  const float radius = peak * 16.0 * lines;
  vec4 a = vec4(0.0), b = vec4(0.0);
  for (int i = 0; i < 16; ++i) {
    const float rho = radius * sqrt((float(i) + 0.5) / 16.0);
    const float th = float(i) * 2.39996323;
    const vec2 o = rho * vec2(cos(th), sin(th));
    a += at0(px + o);
    b += at1(px + o);
  }
  outColor = mix(a, b, p) / 16.0;
#elif HS_PATTERN == 4  // swipe
  outColor = mix(fetch0(ip), fetch1(ip), edge(px.x / gSize.x, p, 0.03));
#elif HS_PATTERN == 9  // radial_wipe
  // A clock hand from twelve o'clock, clockwise.
  float turn = atan(q.x, q.y) / (2.0 * kPi);
  if (turn < 0.0) turn += 1.0;
  outColor = mix(fetch0(ip), fetch1(ip), edge(turn, p, 0.01));
#elif HS_PATTERN == 5  // water_drop
  // A ring from the centre reaching the corners at the end; ahead of it
  // the outgoing shot ripples, the ripple fading as the ring grows.
  const float d = length(q);
  const float reach = p * (0.5 * length(gSize) / gSize.y + 0.04);
  const float ahead = d - reach;
  const vec2 dir = d > 1e-6 ? q / d : vec2(0.0);
  const float amp = 0.015 * (1.0 - p) * exp(-ahead * ahead / 0.004);
  const vec2 offset = dir * amp * sin(ahead * 90.0) * gSize.y;
  outColor = mix(at0(px + offset), fetch1(ip), 1.0 - smoothstep(-0.02, 0.02, ahead));
#elif HS_PATTERN == 6  // pixel_dissolve
  // Blocks growing to 24 px (per 1080 rows) at the middle, each block
  // switching to the incoming shot when the progress passes its number.
  const int block = max(1, int(floor(24.0 * lines * peak + 0.5)));
  const ivec2 cell = ip / block;
  const ivec2 centre = cell * block + block / 2;
  const bool incoming = rand3(uint(cell.x), uint(cell.y), uint(block)) < p;
  outColor = incoming ? fetch1(centre) : fetch0(centre);
#elif HS_PATTERN == 7  // glitch
  // Rows in bands; a band is displaced sideways (more of them mid-way),
  // its channels split, and shows the incoming shot once the progress
  // passes its number. A new pattern every frame.
  const int band = max(2, int(floor(12.0 * lines + 0.5)));
  const uint k = uint(ip.y / band);
  const bool displaced = rand3(k, uFrame, 1u) < 0.6 * peak;
  const int shift = displaced ? int(floor((rand3(k, uFrame, 2u) - 0.5) * 0.2 * gSize.x * peak + 0.5)) : 0;
  const int split = int(floor(6.0 * lines * peak + 0.5));
  const bool incoming = rand3(k, uFrame, 3u) < p;
  const int x = ip.x + shift;
  const vec4 r = incoming ? fetch1(ivec2(x + split, ip.y)) : fetch0(ivec2(x + split, ip.y));
  const vec4 g = incoming ? fetch1(ivec2(x, ip.y)) : fetch0(ivec2(x, ip.y));
  const vec4 b = incoming ? fetch1(ivec2(x - split, ip.y)) : fetch0(ivec2(x - split, ip.y));
  outColor = vec4(r.r, g.g, b.b, g.a);
#elif HS_PATTERN == 8  // zoom_blur
  // 16 taps towards the centre, the streak peaking mid-way.
  const float z = 0.25 * peak;
  vec4 a = vec4(0.0), b = vec4(0.0);
  const vec2 c = 0.5 * gSize;
  for (int i = 0; i < 16; ++i) {
    const vec2 t = c + (px - c) * (1.0 - z * float(i) / 15.0);
    a += at0(t);
    b += at1(t);
  }
  outColor = mix(a, b, smoothstep(0.25, 0.75, p)) / 16.0;
#else
  outColor = weighted(ip);
#endif
#endif
}
