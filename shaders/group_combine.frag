#version 450 core
// View groups combined (render/passes/group_combine.h): the weighted sum of
// up to four groups' linear HDR images of one view, pixel for pixel.
layout(binding = 24) uniform sampler2D uImage0;
layout(binding = 25) uniform sampler2D uImage1;
layout(binding = 26) uniform sampler2D uImage2;
layout(binding = 27) uniform sampler2D uImage3;
uniform vec4 uWeights;
uniform int uImages;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 sum = texelFetch(uImage0, p, 0) * uWeights.x;
  if (uImages > 1) sum += texelFetch(uImage1, p, 0) * uWeights.y;
  if (uImages > 2) sum += texelFetch(uImage2, p, 0) * uWeights.z;
  if (uImages > 3) sum += texelFetch(uImage3, p, 0) * uWeights.w;
  outColor = sum;
}
