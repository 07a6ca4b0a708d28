#version 450 core
// Meshes, camera-relative (frame_blocks.glsl): the object's matrix is
// relative to the frame origin, formed in double on the CPU, so vertices far
// from the world origin arrive here as small floats.
#include "frame_blocks.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 7) in uint aObject;  // per instance: index into objects[]

out vec3 vEyePos;
out vec3 vNormal;
out vec2 vUv;
flat out uint vObject;

void main() {
  Object o = objects[aObject];
  vec3 p = (o.model * vec4(aPosition, 1.0)).xyz - view.eyeOffset.xyz;
  vEyePos = p;
  vNormal = mat3(o.normalMatrix) * aNormal;
  vUv = aUv;
  vObject = aObject;
  gl_Position = view.projection * (view.viewRotation * vec4(p, 1.0));
}
