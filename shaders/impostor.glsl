// Octahedral impostors' atlas geometry: render/impostor_atlas.h is the
// same maths in double (the hemi-octahedral map of frame directions, each
// frame's picture plane, the three frames a view blends). The frame count
// per side and its pixels come from the program's defines IMPOSTOR_FRAMES
// and IMPOSTOR_FRAME_PIXELS (the renderer passes kImpostorFrames and
// kImpostorFramePixels; the defaults here are theirs).
#ifndef HS_IMPOSTOR_GLSL
#define HS_IMPOSTOR_GLSL

#ifndef IMPOSTOR_FRAMES
#define IMPOSTOR_FRAMES 12
#endif
#ifndef IMPOSTOR_FRAME_PIXELS
#define IMPOSTOR_FRAME_PIXELS 64
#endif
const float kImpostorFrames = float(IMPOSTOR_FRAMES);

vec2 impostorEncode(vec3 d) {
  d.z = max(d.z, 0.0);
  float sum = abs(d.x) + abs(d.y) + d.z;
  if (!(sum > 0.0)) return vec2(0.5);
  d /= sum;
  return clamp(vec2(d.x + d.y, d.x - d.y) * 0.5 + 0.5, 0.0, 1.0);
}

vec3 impostorDecode(vec2 g) {
  vec2 e = clamp(g, 0.0, 1.0) * 2.0 - 1.0;
  vec3 d = vec3(0.5 * (e.x + e.y), 0.5 * (e.x - e.y), 0.0);
  d.z = max(0.0, 1.0 - abs(d.x) - abs(d.y));
  return normalize(d);
}

vec3 impostorFrameDirection(vec2 frame) { return impostorDecode(frame / (kImpostorFrames - 1.0)); }

// right = z x d normalised (x straight down); up = d x right.
void impostorBasis(vec3 d, out vec3 right, out vec3 up) {
  right = vec3(-d.y, d.x, 0.0);
  float len = length(right);
  right = len > 1e-6 ? right / len : vec3(1.0, 0.0, 0.0);
  up = normalize(cross(d, right));
}

// The three frames (grid indices) a view from `d` blends, and their weights.
void impostorBlend(vec3 d, out vec2 frames[3], out vec3 weights) {
  vec2 g = impostorEncode(d) * (kImpostorFrames - 1.0);
  vec2 base = clamp(floor(g), vec2(0.0), vec2(kImpostorFrames - 2.0));
  vec2 f = clamp(g - base, 0.0, 1.0);
  if (f.x + f.y <= 1.0) {
    frames[0] = base;
    frames[1] = base + vec2(1.0, 0.0);
    frames[2] = base + vec2(0.0, 1.0);
    weights = vec3(1.0 - f.x - f.y, f.x, f.y);
  } else {
    frames[0] = base + vec2(1.0, 1.0);
    frames[1] = base + vec2(0.0, 1.0);
    frames[2] = base + vec2(1.0, 0.0);
    weights = vec3(f.x + f.y - 1.0, 1.0 - f.x, 1.0 - f.y);
  }
}

#endif
