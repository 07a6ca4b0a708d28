#version 450 core
// Anisotropic Kuwahara, step 1 of 3 (render/passes/stylised_passes.h): the
// structure tensor of the image, from Sobel derivatives of each channel
// summed: (E, G, F) = sum over channels of (gx², gy², gx·gy).
layout(binding = 0) uniform sampler2D uImage;
layout(location = 0) out vec4 outColor;

vec3 at(ivec2 p) { return texelFetch(uImage, clamp(p, ivec2(0), textureSize(uImage, 0) - 1), 0).rgb; }

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec3 tl = at(p + ivec2(-1, 1)), t = at(p + ivec2(0, 1)), tr = at(p + ivec2(1, 1));
  const vec3 l = at(p + ivec2(-1, 0)), r = at(p + ivec2(1, 0));
  const vec3 bl = at(p + ivec2(-1, -1)), b = at(p + ivec2(0, -1)), br = at(p + ivec2(1, -1));
  const vec3 gx = ((tr + 2.0 * r + br) - (tl + 2.0 * l + bl)) * 0.25;
  const vec3 gy = ((tl + 2.0 * t + tr) - (bl + 2.0 * b + br)) * 0.25;
  outColor = vec4(dot(gx, gx), dot(gy, gy), dot(gx, gy), 1.0);
}
