#version 450 core
// One level of the prefiltered specular cube: the radiance cube convolved
// with the GGX lobe of this level's roughness (Karis's split sum, with
// n = v = r), by importance sampling with filtered lookups (Krivanek and
// Colbert: each sample reads the mip whose texel matches its solid angle,
// so 32 samples give a smooth result).
#include "cube_common.glsl"
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba16f, binding = 0) uniform writeonly imageCube uOut;
layout(binding = 0) uniform samplerCube uRadiance;
uniform int uSize;           // this level's size
uniform float uRoughness;    // perceptual
uniform float uSourceSize;   // the radiance cube's level 0 size
const uint kSamples = 32u;
const float kPi = 3.14159265358979;

vec2 hammersley(uint i) {
  uint b = bitfieldReverse(i);
  return vec2(float(i) / float(kSamples), float(b) * 2.3283064365386963e-10);
}

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= uSize || id.y >= uSize) return;
  vec3 n = cubeTexelDirection(id.z, id.xy, uSize);
  if (uRoughness <= 0.0) {
    imageStore(uOut, id, vec4(textureLod(uRadiance, n, 0.0).rgb, 1.0));
    return;
  }
  vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 tx = normalize(cross(up, n)), ty = cross(n, tx);
  float a = uRoughness * uRoughness, a2 = a * a;
  float texelAngle = 4.0 * kPi / (6.0 * uSourceSize * uSourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (uint i = 0u; i < kSamples; ++i) {
    vec2 u = hammersley(i);
    float cosH = sqrt((1.0 - u.y) / (1.0 + (a2 - 1.0) * u.y));
    float sinH = sqrt(1.0 - cosH * cosH), phi = 2.0 * kPi * u.x;
    vec3 h = tx * (sinH * cos(phi)) + ty * (sinH * sin(phi)) + n * cosH;
    vec3 l = 2.0 * dot(n, h) * h - n;
    float nl = dot(n, l);
    if (nl <= 0.0) continue;
    float d = (cosH * cosH * (a2 - 1.0) + 1.0);
    float D = a2 / (kPi * d * d);
    float pdf = D * 0.25;  // D cosH / (4 v.h) with n = v
    float sampleAngle = 1.0 / (float(kSamples) * pdf + 1e-4);
    float lod = max(0.5 * log2(sampleAngle / texelAngle) + 1.0, 0.0);
    sum += textureLod(uRadiance, l, lod).rgb * nl;
    weight += nl;
  }
  imageStore(uOut, id, vec4(sum / max(weight, 1e-4), 1.0));
}
