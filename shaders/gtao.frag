#version 450 core
// Ground-truth-based ambient occlusion (settings.ao = gtao; Jimenez, Wu,
// Pesce and Jarabo, "Practical Realtime Strategies for Accurate Indirect
// Occlusion", 2016, as in Intel's XeGTAO): for each of kSlices screen
// directions through the pixel, the highest horizon on both sides within
// uRadius metres (kSteps depth samples a side), then the cosine-weighted
// visible arc between the two horizons, integrated in closed form against
// the normal projected into the slice. Unlike ssao.frag's point samples it
// integrates the visible hemisphere, so an open plane gives exactly 1 and a
// corner the cosine-weighted share of sky it sees. Occluders are taken as
// infinitely thick (a depth buffer's heightfield). Positions come from the
// reversed-Z depth through the inverse projection; the normal from the
// nearer neighbour on each axis (no smearing over depth edges). Output:
// visibility, 1 = open; uStrength scales the occlusion as for ssao.frag.
#include "frame_blocks.glsl"
in vec2 vUv;
layout(binding = 0) uniform sampler2D uDepth;
uniform mat4 uInvProjection;
uniform float uRadius;
uniform float uStrength;
layout(location = 0) out float outAo;

const int kSlices = 4;
const int kSteps = 8;
const float kPi = 3.14159265;

vec3 viewPosition(vec2 uv, float depth) {
  vec4 p = uInvProjection * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}

vec3 positionAt(vec2 uv) { return viewPosition(uv, texture(uDepth, uv).r); }

float fastAcos(float x) { return acos(clamp(x, -1.0, 1.0)); }

void main() {
  float depth = texture(uDepth, vUv).r;
  if (depth <= 0.0) {  // the sky: nothing to occlude
    outAo = 1.0;
    return;
  }
  vec2 texel = 1.0 / vec2(textureSize(uDepth, 0));
  vec3 p = viewPosition(vUv, depth);
  // The normal from the neighbours on the nearer side of each axis.
  vec3 l = positionAt(vUv - vec2(texel.x, 0.0)), r = positionAt(vUv + vec2(texel.x, 0.0));
  vec3 b = positionAt(vUv - vec2(0.0, texel.y)), t = positionAt(vUv + vec2(0.0, texel.y));
  vec3 dx = abs(r.z - p.z) < abs(p.z - l.z) ? r - p : p - l;
  vec3 dy = abs(t.z - p.z) < abs(p.z - b.z) ? t - p : p - b;
  vec3 n = normalize(cross(dx, dy));
  vec3 v = normalize(-p);
  if (dot(n, v) < 0.0) n = -n;

  // Horizons fade out linearly from 0.75 to 1.25 radius, so an occluder
  // counts as "within the radius" on average (XeGTAO fades from 0.385 and
  // scales its radius by 1.457 for the same reason) and a far one not at
  // all; samples reach the fade's end.
  float reach = 1.25 * uRadius;
  float falloffMul = -1.0 / (0.5 * uRadius);
  float falloffAdd = reach / (0.5 * uRadius);
  // The reach on screen (pixels of the depth texture) at this depth.
  float pixelsPerMetre = 0.5 * float(textureSize(uDepth, 0).y) * view.projection[1][1] / max(-p.z, 1e-4);
  float screenRadius = reach * pixelsPerMetre;
  if (screenRadius < 1.0) {  // the radius is under a pixel: nothing to find
    outAo = 1.0;
    return;
  }

  // Interleaved gradient noise turns the slices and offsets the steps per
  // pixel; ssao_apply.frag's 4 x 4 blur averages it.
  float noise = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
  float noise2 = fract(noise * 1.61803398 + 0.5);
  float visibility = 0.0;
  for (int slice = 0; slice < kSlices; ++slice) {
    float phi = (float(slice) + noise) * kPi / float(kSlices);
    vec2 omega = vec2(cos(phi), sin(phi));
    vec3 dir = vec3(omega, 0.0);
    vec3 orthoDir = dir - dot(dir, v) * v;
    vec3 axis = normalize(cross(orthoDir, v));
    vec3 projN = n - axis * dot(n, axis);
    float projLen = length(projN);
    float cosN = clamp(dot(projN, v) / max(projLen, 1e-6), 0.0, 1.0);
    float gamma = sign(dot(orthoDir, projN)) * fastAcos(cosN);
    // Lowest horizons: the slice's tangent plane.
    float low0 = cos(gamma + 0.5 * kPi), low1 = cos(gamma - 0.5 * kPi);
    float h0 = low0, h1 = low1;
    for (int s = 0; s < kSteps; ++s) {
      // Steps spread quadratically: denser near the pixel.
      float f = (float(s) + noise2) / float(kSteps);
      vec2 offset = omega * max(f * f * screenRadius, float(s) + 1.0) * texel;
      vec3 q0 = positionAt(vUv + offset) - p;
      vec3 q1 = positionAt(vUv - offset) - p;
      float d0 = length(q0), d1 = length(q1);
      float c0 = dot(q0 / max(d0, 1e-6), v), c1 = dot(q1 / max(d1, 1e-6), v);
      float w0 = clamp(d0 * falloffMul + falloffAdd, 0.0, 1.0), w1 = clamp(d1 * falloffMul + falloffAdd, 0.0, 1.0);
      h0 = max(h0, mix(low0, c0, w0));
      h1 = max(h1, mix(low1, c1, w1));
    }
    // h0 lies on the +omega side, h1 on the -omega side.
    float a1 = fastAcos(h0), a0 = -fastAcos(h1);
    a0 = gamma + max(a0 - gamma, -0.5 * kPi);
    a1 = gamma + min(a1 - gamma, 0.5 * kPi);
    float arc0 = (cosN + 2.0 * a0 * sin(gamma) - cos(2.0 * a0 - gamma)) * 0.25;
    float arc1 = (cosN + 2.0 * a1 * sin(gamma) - cos(2.0 * a1 - gamma)) * 0.25;
    visibility += projLen * (arc0 + arc1);
  }
  visibility /= float(kSlices);
  outAo = clamp(1.0 - uStrength * (1.0 - visibility), 0.0, 1.0);
}
