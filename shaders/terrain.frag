#version 450 core
// Terrain shading: holes and the area past the last sample discarded,
// per-pixel normals from the height texture, splat materials blended by the
// paint weights (albedo colour x texture, tangent-space normal maps,
// roughness, tiling), lit like the meshes (lighting.glsl).
#include "lighting.glsl"

in vec3 vEyePos;
in vec2 vSample;
in vec2 vLocal;

uniform sampler2D uHeight;
uniform ivec2 uSamples;
uniform vec2 uSpacing;
uniform bool uHasHoles;
uniform usampler2D uHoles;

const int MAX_LAYERS = 16;
uniform int uLayerCount;
uniform int uWeightSlice[MAX_LAYERS];    // slice s: channel s % 4 of uWeights' layer s / 4; -1: uWeightConst
uniform float uWeightConst[MAX_LAYERS];
uniform int uWeightGroups;               // uWeights' layers (four slices each)
uniform sampler2DArray uWeights;
uniform vec3 uAlbedo[MAX_LAYERS];        // linear
uniform float uRoughness[MAX_LAYERS];
uniform float uTiling[MAX_LAYERS];       // metres per texture repeat
uniform int uAlbedoLayer[MAX_LAYERS];    // slice of uAlbedoTex, or -1
uniform int uNormalLayer[MAX_LAYERS];    // slice of uNormalTex, or -1
uniform sampler2DArray uAlbedoTex;       // sRGB: sampled as linear
uniform sampler2DArray uNormalTex;

layout(location = 0) out vec4 outColor;

float h(vec2 s) { return textureLod(uHeight, (s + 0.5) / vec2(uSamples), 0.0).r; }

void main() {
  // The grid extends past the last sample where a level's quads do not fit.
  const vec2 last = vec2(uSamples - 1);
  if (any(lessThan(vSample, vec2(-1e-3))) || any(greaterThan(vSample, last + 1e-3))) discard;
  if (uHasHoles) {
    // A cell is a hole when any of its corners is marked (heightfield.h).
    ivec2 c = clamp(ivec2(floor(vSample)), ivec2(0), uSamples - 2);
    if (texelFetch(uHoles, c, 0).r + texelFetch(uHoles, c + ivec2(1, 0), 0).r +
        texelFetch(uHoles, c + ivec2(0, 1), 0).r + texelFetch(uHoles, c + ivec2(1, 1), 0).r > 0u)
      discard;
  }
  // Bilinear central differences (linear in the samples: the same as
  // interpolating the per-sample gradients, as Heightfield::normalAtLocal).
  float gx = (h(vSample + vec2(1, 0)) - h(vSample - vec2(1, 0))) / (2.0 * uSpacing.x);
  float gy = (h(vSample + vec2(0, 1)) - h(vSample - vec2(0, 1))) / (2.0 * uSpacing.y);
  vec3 N = normalize(vec3(-gx, -gy, 1.0));
  vec3 T = normalize(vec3(1.0, 0.0, gx));
  vec3 B = normalize(cross(N, T));

  vec3 albedo = vec3(0.0);
  vec3 tn = vec3(0.0);
  float rough = 0.0, total = 0.0;
  vec2 wuv = (vSample + 0.5) / vec2(uSamples);
  // Every painted weight in one fetch per four layers (gpu_terrain.h).
  // Named vectors and a channel mask rather than an indexed array, which
  // llvmpipe keeps in memory.
  vec4 w0 = vec4(0.0), w1 = vec4(0.0), w2 = vec4(0.0), w3 = vec4(0.0);
  if (uWeightGroups > 0) w0 = texture(uWeights, vec3(wuv, 0.0));
  if (uWeightGroups > 1) w1 = texture(uWeights, vec3(wuv, 1.0));
  if (uWeightGroups > 2) w2 = texture(uWeights, vec3(wuv, 2.0));
  if (uWeightGroups > 3) w3 = texture(uWeights, vec3(wuv, 3.0));
  for (int i = 0; i < uLayerCount; ++i) {
    const int slice = uWeightSlice[i];
    const int g = slice >> 2;
    const vec4 group = g == 0 ? w0 : (g == 1 ? w1 : (g == 2 ? w2 : w3));
    float w = slice < 0 ? uWeightConst[i] : dot(group, vec4(equal(ivec4(0, 1, 2, 3), ivec4(slice & 3))));
    if (w < 1e-3) continue;
    vec2 uv = vLocal / uTiling[i];
    vec3 a = uAlbedo[i];
    if (uAlbedoLayer[i] >= 0) a *= texture(uAlbedoTex, vec3(uv, float(uAlbedoLayer[i]))).rgb;
    vec3 n = vec3(0.0, 0.0, 1.0);
    if (uNormalLayer[i] >= 0) n = texture(uNormalTex, vec3(uv, float(uNormalLayer[i]))).rgb * 2.0 - 1.0;
    albedo += w * a;
    tn += w * n;
    rough += w * uRoughness[i];
    total += w;
  }
  if (total > 0.0) {
    albedo /= total;
    rough /= total;
    tn /= total;
  } else {
    albedo = vec3(0.5);
    rough = 0.8;
    tn = vec3(0.0, 0.0, 1.0);
  }
  vec3 n = normalize(T * tn.x + B * tn.y + N * max(tn.z, 1e-3));
  // Roughness to a Blinn-Phong exponent and a dielectric highlight.
  float r2 = max(rough * rough, 0.02);
  float shininess = clamp(2.0 / (r2 * r2) - 2.0, 2.0, 512.0);
  float specular = 0.04 * (1.0 - rough) * (shininess + 8.0) / 8.0;
  outColor = vec4(lightSurface(albedo, vEyePos, n, shininess, specular), hsAmbientShare);
}
