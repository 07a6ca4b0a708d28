#version 450 core
// The editor's before/after split (RenderOptions::postSplit): the frame
// without its post effects drawn over the left part of the finished one,
// with a line at the border.
layout(binding = 0) uniform sampler2D uBefore;
uniform float uSplitX;  // pixels from the left
layout(location = 0) out vec4 outColor;

void main() {
  const float d = gl_FragCoord.x - uSplitX;
  if (d > 1.0) discard;
  outColor = abs(d) <= 1.0 ? vec4(0.92, 0.92, 0.95, 1.0) : vec4(texelFetch(uBefore, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
