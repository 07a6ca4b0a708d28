#version 450 core
// Anisotropic Kuwahara, step 3 of 3 (Kyprianidis, Kang & Doellner 2009;
// the polynomial sector weights of Kyprianidis, Semmo, Kang & Doellner
// 2010): over an ellipse laid along the local structure (stretched by the
// anisotropy), eight overlapping sectors each give a weighted mean and
// variance; the output blends the means, a sector weighing
// 1 / (1 + (255 sigma²)^(q/2)), so the least varied sectors win and edges
// stay sharp. q is at most 16 (PostSettings), so no weight underflows a
// float even at the largest variance (765^8 < 1e24); a pixel whose
// sectors all lack weight keeps its colour.
layout(binding = 0) uniform sampler2D uImage;
layout(binding = 1) uniform sampler2D uOrientation;
uniform float uRadius;  // pixels
uniform float uQ;
layout(location = 0) out vec4 outColor;

void main() {
  const ivec2 size = textureSize(uImage, 0);
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec4 o = texelFetch(uOrientation, p, 0);
  const float alpha = 1.0;
  const float a = uRadius * clamp((alpha + o.z) / alpha, 0.1, 2.0);
  const float b = uRadius * clamp(alpha / (alpha + o.z), 0.1, 2.0);
  const float cp = o.x, sp = o.y;
  // Into the ellipse's frame, scaled so that its boundary is at 0.5.
  const mat2 sr = mat2(0.5 / a, 0.0, 0.0, 0.5 / b) * mat2(cp, -sp, sp, cp);
  const int maxX = int(sqrt(a * a * cp * cp + b * b * sp * sp));
  const int maxY = int(sqrt(a * a * sp * sp + b * b * cp * cp));
  const float zeta = 2.0 / max(uRadius, 1.0);
  const float zeroCross = 0.58;
  const float sinZero = sin(zeroCross);
  const float eta = (zeta + cos(zeroCross)) / (sinZero * sinZero);
  vec4 m[8];
  vec3 s[8];
  for (int k = 0; k < 8; ++k) m[k] = vec4(0.0), s[k] = vec3(0.0);
  for (int j = -maxY; j <= maxY; ++j)
    for (int i = -maxX; i <= maxX; ++i) {
      vec2 v = sr * vec2(float(i), float(j));
      if (dot(v, v) > 0.25) continue;
      const vec3 c = texelFetch(uImage, clamp(p + ivec2(i, j), ivec2(0), size - 1), 0).rgb;
      float w[8];
      float sum = 0.0;
      float vxx = zeta - eta * v.x * v.x, vyy = zeta - eta * v.y * v.y;
      float z;
      z = max(0.0, v.y + vxx); w[0] = z * z; sum += w[0];
      z = max(0.0, -v.x + vyy); w[2] = z * z; sum += w[2];
      z = max(0.0, -v.y + vxx); w[4] = z * z; sum += w[4];
      z = max(0.0, v.x + vyy); w[6] = z * z; sum += w[6];
      v = 0.70710678 * vec2(v.x - v.y, v.x + v.y);
      vxx = zeta - eta * v.x * v.x;
      vyy = zeta - eta * v.y * v.y;
      z = max(0.0, v.y + vxx); w[1] = z * z; sum += w[1];
      z = max(0.0, -v.x + vyy); w[3] = z * z; sum += w[3];
      z = max(0.0, -v.y + vxx); w[5] = z * z; sum += w[5];
      z = max(0.0, v.x + vyy); w[7] = z * z; sum += w[7];
      if (sum <= 0.0) continue;
      const float g = exp(-3.125 * dot(v, v)) / sum;
      for (int k = 0; k < 8; ++k) {
        const float wk = w[k] * g;
        m[k] += vec4(c * wk, wk);
        s[k] += c * c * wk;
      }
    }
  vec3 result = vec3(0.0);
  float total = 0.0;
  for (int k = 0; k < 8; ++k) {
    if (m[k].w <= 0.0) continue;
    const vec3 mean = m[k].rgb / m[k].w;
    const vec3 var = abs(s[k] / m[k].w - mean * mean);
    const float w = 1.0 / (1.0 + pow(255.0 * (var.r + var.g + var.b), 0.5 * uQ));
    result += mean * w;
    total += w;
  }
  outColor = vec4(total > 0.0 ? result / total : texelFetch(uImage, p, 0).rgb, 1.0);
}
