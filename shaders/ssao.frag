#version 450 core
// Screen-space ambient occlusion (settings.ao = ssao): for each pixel, the
// share of 16 points in the normal-oriented hemisphere of radius uRadius
// (metres) that lie behind the depth buffer, with a range check so a
// distant occluder does not count (Crytek's SSAO with the normal
// hemisphere of Bavoil and Sainz's HBAO paper's framing). Positions come
// from the reversed-Z depth through the inverse projection; normals from
// the positions' screen-space derivatives. Output: visibility, 1 = open.
#include "frame_blocks.glsl"
in vec2 vUv;
layout(binding = 0) uniform sampler2D uDepth;
uniform mat4 uInvProjection;
uniform float uRadius;
uniform float uStrength;
layout(location = 0) out float outAo;

vec3 viewPosition(vec2 uv, float depth) {
  vec4 p = uInvProjection * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return p.xyz / p.w;
}

void main() {
  float depth = texture(uDepth, vUv).r;
  if (depth <= 0.0) {  // the sky: nothing to occlude
    outAo = 1.0;
    return;
  }
  vec3 p = viewPosition(vUv, depth);
  vec3 n = normalize(cross(dFdx(p), dFdy(p)));
  if (dot(n, p) > 0.0) n = -n;  // towards the eye
  // A rotation per pixel (interleaved gradient noise) turns the fixed
  // kernel, trading banding for noise the apply pass blurs.
  float angle = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
  vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = normalize(cross(helper, n)), b = cross(n, t);
  float occluded = 0.0;
  const int kSamples = 16;
  for (int i = 0; i < kSamples; ++i) {
    // A golden-angle spiral over the hemisphere (cosine-weighted
    // directions), lengths spread evenly from a fifth of the radius to it.
    float fi = (float(i) + 0.5) / float(kSamples);
    float phi = angle + float(i) * 2.39996323;
    float cosT = sqrt(1.0 - fi), sinT = sqrt(fi);
    vec3 dir = t * (cos(phi) * sinT) + b * (sin(phi) * sinT) + n * cosT;
    float len = uRadius * mix(0.2, 1.0, fract(float(i) * 0.618034 + 0.5));
    vec3 q = p + dir * len;
    vec4 clip = view.projection * vec4(q, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
    float d = texture(uDepth, uv).r;
    if (d <= 0.0) continue;
    float sceneZ = viewPosition(uv, d).z;
    // In front of the sample point (nearer the eye: larger z) occludes it,
    // fading out when the occluder is farther than the radius from p.
    float range = smoothstep(0.0, 1.0, uRadius / max(abs(p.z - sceneZ), 1e-4));
    occluded += (sceneZ > q.z + 0.02 * uRadius ? 1.0 : 0.0) * range;
  }
  outAo = clamp(1.0 - uStrength * occluded / float(kSamples), 0.0, 1.0);
}
