#version 450 core
// Bakes one frame of an octahedral impostor (render/impostor_cache.h):
// level 0 of a mesh, orthographic along the frame's direction (shaders/
// impostor.glsl), its bounding sphere filling the frame's square. Depth is
// reversed as the renderer's ([0, 1], nearer the viewer larger), the
// sphere's near pole at 1.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform vec4 uSphere;  // centre (mesh space), radius
uniform vec3 uFrameDir;    // towards the viewer
uniform vec3 uFrameRight;
uniform vec3 uFrameUp;

out vec3 vNormal;
out vec2 vUv;

void main() {
  vec3 q = (aPosition - uSphere.xyz) / uSphere.w;
  // 0.499: a vertex on the sphere itself stays inside the depth range.
  gl_Position = vec4(dot(q, uFrameRight), dot(q, uFrameUp), 0.5 + 0.499 * dot(q, uFrameDir), 1.0);
  vNormal = aNormal;
  vUv = aUv;
}
