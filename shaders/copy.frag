#version 450 core
// A texture drawn as it is (the end of a chain whose last step was a
// compute pass, which cannot write the caller's framebuffer).
layout(binding = 0) uniform sampler2D uImage;
layout(location = 0) out vec4 outColor;

void main() { outColor = texelFetch(uImage, ivec2(gl_FragCoord.xy), 0); }
