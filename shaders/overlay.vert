#version 450 core
// Editor overlays (gizmo, bounds, camera paths): camera-relative positions
// prepared on the CPU, flat colour per vertex.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;
uniform mat4 uViewRot;
uniform mat4 uProjection;
out vec4 vColor;
void main() {
  vColor = aColor;
  gl_Position = uProjection * uViewRot * vec4(aPosition, 1.0);
}
