#version 450 core
// FXAA (after Lottes' FXAA 3.11 quality preset idea, simplified): find
// edges by luma contrast, blend along them. Input is sRGB with luma in alpha.
in vec2 vUv;
layout(binding = 0) uniform sampler2D uImage;
uniform vec2 uTexel;  // 1 / size
layout(location = 0) out vec4 outColor;

const float EDGE_MIN = 1.0 / 24.0;
const float EDGE_REL = 1.0 / 8.0;
const float SPAN_MAX = 8.0;
const float REDUCE_MUL = 1.0 / 8.0;
const float REDUCE_MIN = 1.0 / 128.0;

void main() {
  float lumaM = texture(uImage, vUv).a;
  float lumaNW = textureOffset(uImage, vUv, ivec2(-1, -1)).a;
  float lumaNE = textureOffset(uImage, vUv, ivec2(1, -1)).a;
  float lumaSW = textureOffset(uImage, vUv, ivec2(-1, 1)).a;
  float lumaSE = textureOffset(uImage, vUv, ivec2(1, 1)).a;
  float lumaMin = min(lumaM, min(min(lumaNW, lumaNE), min(lumaSW, lumaSE)));
  float lumaMax = max(lumaM, max(max(lumaNW, lumaNE), max(lumaSW, lumaSE)));
  if (lumaMax - lumaMin < max(EDGE_MIN, lumaMax * EDGE_REL)) {
    outColor = vec4(texture(uImage, vUv).rgb, 1.0);
    return;
  }
  vec2 dir = vec2(-((lumaNW + lumaNE) - (lumaSW + lumaSE)), (lumaNW + lumaSW) - (lumaNE + lumaSE));
  float reduce = max((lumaNW + lumaNE + lumaSW + lumaSE) * 0.25 * REDUCE_MUL, REDUCE_MIN);
  float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
  dir = clamp(dir * scale, vec2(-SPAN_MAX), vec2(SPAN_MAX)) * uTexel;
  vec3 a = 0.5 * (texture(uImage, vUv + dir * (1.0 / 3.0 - 0.5)).rgb +
                  texture(uImage, vUv + dir * (2.0 / 3.0 - 0.5)).rgb);
  vec3 b = a * 0.5 + 0.25 * (texture(uImage, vUv - dir * 0.5).rgb + texture(uImage, vUv + dir * 0.5).rgb);
  float lumaB = dot(b, vec3(0.299, 0.587, 0.114));
  outColor = vec4((lumaB < lumaMin || lumaB > lumaMax) ? a : b, 1.0);
}
