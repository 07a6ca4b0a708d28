#version 450 core
// Blinn-Phong from the sun, hemispheric sky ambient, point lights.
in vec3 vViewPos;
in vec3 vViewNormal;
in vec2 vUv;

uniform vec4 uBaseColor;       // linear
uniform bool uHasTexture;
uniform sampler2D uAlbedo;     // sRGB texture: sampled as linear
uniform vec3 uSunDirView;      // towards the sun, view space
uniform vec3 uSunColor;        // linear, intensity applied
uniform bool uHasSun;
uniform vec3 uUpView;          // world +Z in view space
uniform vec3 uSkyColor;
uniform vec3 uGroundColor;
uniform float uAmbient;
uniform float uShininess;
uniform float uSpecular;

const int MAX_POINT_LIGHTS = 8;
uniform int uPointLightCount;
uniform vec3 uPointPosView[MAX_POINT_LIGHTS];
uniform vec3 uPointColor[MAX_POINT_LIGHTS];
uniform float uPointRange[MAX_POINT_LIGHTS];

layout(location = 0) out vec4 outColor;

void main() {
  vec4 albedo = uBaseColor;
  if (uHasTexture) albedo *= texture(uAlbedo, vUv);
  vec3 n = normalize(vViewNormal);
  vec3 v = normalize(-vViewPos);
  // Scans are often open surfaces seen from behind: light the side we see.
  if (!gl_FrontFacing) n = -n;

  float up = dot(n, uUpView) * 0.5 + 0.5;
  vec3 color = albedo.rgb * mix(uGroundColor, uSkyColor, up) * uAmbient;

  if (uHasSun) {
    float ndl = max(dot(n, uSunDirView), 0.0);
    vec3 h = normalize(uSunDirView + v);
    float spec = ndl > 0.0 ? pow(max(dot(n, h), 0.0), uShininess) * uSpecular : 0.0;
    color += (albedo.rgb * ndl + vec3(spec)) * uSunColor;
  }
  for (int i = 0; i < uPointLightCount; ++i) {
    vec3 toLight = uPointPosView[i] - vViewPos;
    float d = length(toLight);
    vec3 l = toLight / max(d, 1e-4);
    // Inverse square, windowed to zero at the range (no hard cut-off).
    float window = clamp(1.0 - pow(d / uPointRange[i], 4.0), 0.0, 1.0);
    float atten = window * window / max(d * d, 1e-4);
    float ndl = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float spec = ndl > 0.0 ? pow(max(dot(n, h), 0.0), uShininess) * uSpecular : 0.0;
    color += (albedo.rgb * ndl + vec3(spec)) * uPointColor[i] * atten;
  }
  outColor = vec4(color, albedo.a);
}
