#version 450 core
// Sky gradient behind everything: drawn last where the depth buffer is
// still clear, so covered pixels cost nothing.
in vec2 vUv;
uniform mat3 uInvViewRot;   // view to world rotation
uniform vec2 uTanHalfFov;   // tan(fovY/2) * aspect, tan(fovY/2)
uniform vec2 uSubpixel;     // projection offset (stereo/off-axis later)
uniform vec3 uZenith;
uniform vec3 uHorizon;
uniform vec3 uGround;
uniform vec3 uSunDirWorld;
uniform vec3 uSunColor;
uniform bool uHasSun;
layout(location = 0) out vec4 outColor;

void main() {
  vec2 ndc = vUv * 2.0 - 1.0 - uSubpixel;  // the projection added the shift
  vec3 dirView = normalize(vec3(ndc * uTanHalfFov, -1.0));
  vec3 dir = uInvViewRot * dirView;
  float z = dir.z;
  vec3 c;
  if (z >= 0.0)
    c = mix(uHorizon, uZenith, pow(z, 0.55));
  else
    c = mix(uHorizon, uGround, 1.0 - pow(1.0 + z, 8.0));
  if (uHasSun) {
    float s = max(dot(dir, uSunDirWorld), 0.0);
    c += uSunColor * (pow(s, 1200.0) * 8.0 + pow(s, 24.0) * 0.08);
  }
  outColor = vec4(c, 1.0);
}
