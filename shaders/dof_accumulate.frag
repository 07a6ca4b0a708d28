#version 450 core
// Depth of field, reference (render/dof_reference.h): adds one pinhole
// frame's HDR colour, weighted 1/N, into the float accumulation (additive
// blending onto an RGBA32F target).
layout(binding = 24) uniform sampler2D uFrame;
uniform float uWeight;
layout(location = 0) out vec4 outColor;

void main() { outColor = texelFetch(uFrame, ivec2(gl_FragCoord.xy), 0) * uWeight; }
