#version 450 core
// Anti-aliased 1 m and 10 m grid lines, fading with distance. uOffset is the
// camera position modulo 100 m (taken in double on the CPU), so lines stay
// steady at UTM coordinates.
in vec2 vRelXY;
uniform vec2 uOffset;
uniform vec2 uCameraXY;     // for the world axes only; precision loss far away is harmless
uniform float uCameraZ;
uniform float uFadeDistance;
layout(location = 0) out vec4 outColor;

float lineMask(vec2 p, float spacing) {
  vec2 g = p / spacing;
  vec2 w = fwidth(g);
  vec2 d = abs(fract(g - 0.5) - 0.5) / max(w, vec2(1e-6));
  return 1.0 - min(min(d.x, d.y), 1.0);
}

void main() {
  vec2 p = vRelXY + uOffset;
  float dist = length(vec3(vRelXY, uCameraZ));
  float fade = clamp(1.0 - dist / uFadeDistance, 0.0, 1.0);
  float minor = lineMask(p, 1.0) * 0.25 * clamp(1.0 - dist / (uFadeDistance * 0.15), 0.0, 1.0);
  float major = lineMask(p, 10.0) * 0.55;
  float a = max(minor, major) * fade;
  vec3 color = vec3(0.05);
  // World X axis (y = 0) red, Y axis (x = 0) green, as in Blender.
  vec2 world = vRelXY + uCameraXY;
  vec2 w = fwidth(world);
  float xAxis = 1.0 - min(abs(world.y) / max(w.y * 1.5, 1e-6), 1.0);
  float yAxis = 1.0 - min(abs(world.x) / max(w.x * 1.5, 1e-6), 1.0);
  if (xAxis > 0.0) { color = mix(color, vec3(0.8, 0.1, 0.1), xAxis); a = max(a, xAxis * 0.8 * fade); }
  if (yAxis > 0.0) { color = mix(color, vec3(0.2, 0.7, 0.1), yAxis); a = max(a, yAxis * 0.8 * fade); }
  outColor = vec4(color, a);
}
