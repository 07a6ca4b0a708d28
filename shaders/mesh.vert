#version 450 core
// Camera-relative: uModelView was formed in double precision on the CPU
// (world transform minus the camera position), so vertices far from the
// world origin arrive here as small floats.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform mat4 uModelView;
uniform mat3 uNormalMatrix;
uniform mat4 uProjection;

out vec3 vViewPos;
out vec3 vViewNormal;
out vec2 vUv;

void main() {
  vec4 viewPos = uModelView * vec4(aPosition, 1.0);
  vViewPos = viewPos.xyz;
  vViewNormal = uNormalMatrix * aNormal;
  vUv = aUv;
  gl_Position = uProjection * viewPos;
}
