// Direct light from the sun and the scene's lights on a surface.
#ifndef HS_LIGHTS_GLSL
#define HS_LIGHTS_GLSL
#include "brdf.glsl"
#include "frame_blocks.glsl"
#include "shadows.glsl"

vec3 directLighting(Surface s) {
  vec3 color = vec3(0.0);
  if (frame.sunDir.w > 0.5)
    color += reflectLight(s, frame.sunDir.xyz) * frame.sunColor.rgb * sunVisibility(s.position, s.normal);
  int count = int(frame.params.z);
  for (int i = 0; i < count; ++i) {
    vec3 toLight = lights[i].position.xyz - view.eyeOffset.xyz - s.position;
    float d = length(toLight);
    vec3 l = toLight / max(d, 1e-4);
    // Inverse square, windowed to zero at the range (no hard cut-off).
    float window = clamp(1.0 - pow(d / lights[i].position.w, 4.0), 0.0, 1.0);
    float atten = window * window / max(d * d, 1e-4);
    color += reflectLight(s, l) * lights[i].color.rgb * atten * lightVisibility(i, s.position, s.normal);
  }
  return color;
}

#endif
