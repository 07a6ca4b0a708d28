#version 450 core
// A ground plane (z = 0) around the camera, in camera-relative coordinates.
#include "frame_blocks.glsl"
uniform float uCameraZ;     // camera height above z = 0
uniform float uExtent;      // half size of the plane, metres
out vec2 vRelXY;            // position relative to the camera
void main() {
  vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
  vRelXY = corner * uExtent;
  gl_Position = view.projection * view.viewRotation * vec4(vRelXY, -uCameraZ, 1.0);
}
