#version 450 core
// Editor overlays (gizmo, bounds, camera paths): camera-relative positions
// prepared on the CPU, flat colour per vertex.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;
#include "frame_blocks.glsl"
out vec4 vColor;
void main() {
  vColor = aColor;
  gl_Position = view.projection * view.viewRotation * vec4(aPosition, 1.0);
}
