// The lighting of every lit surface (meshes, terrain; later foliage and
// particles), written once. Eye space (frame_blocks.glsl): world axes,
// origin at the eye, so no view rotation enters the lighting.
#include "frame_blocks.glsl"

// Blinn-Phong from the sun and the point lights with a hemispheric sky
// ambient. `p` is the surface position and `n` its unit normal (eye space).
vec3 lightSurface(vec3 albedo, vec3 p, vec3 n, float shininess, float specular) {
  vec3 v = normalize(-p);
  float up = n.z * 0.5 + 0.5;
  vec3 color = albedo * mix(frame.groundColor.rgb, frame.skyZenith.rgb, up) * frame.params.x;
  if (frame.sunDir.w > 0.5) {
    vec3 l = frame.sunDir.xyz;
    float ndl = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float spec = ndl > 0.0 ? pow(max(dot(n, h), 0.0), shininess) * specular : 0.0;
    color += (albedo * ndl + vec3(spec)) * frame.sunColor.rgb;
  }
  int count = int(frame.params.z);
  for (int i = 0; i < count; ++i) {
    vec3 toLight = lights[i].position.xyz - view.eyeOffset.xyz - p;
    float d = length(toLight);
    vec3 l = toLight / max(d, 1e-4);
    // Inverse square, windowed to zero at the range (no hard cut-off).
    float window = clamp(1.0 - pow(d / lights[i].position.w, 4.0), 0.0, 1.0);
    float atten = window * window / max(d * d, 1e-4);
    float ndl = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float spec = ndl > 0.0 ? pow(max(dot(n, h), 0.0), shininess) * specular : 0.0;
    color += (albedo * ndl + vec3(spec)) * lights[i].color.rgb * atten;
  }
  return color;
}
