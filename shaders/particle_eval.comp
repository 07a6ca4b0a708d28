#version 450 core
// One emitter's particles at scene time t, evaluated in closed form
// (render/particle_gpu_eval.h; the CPU reference is particles/evaluate.cpp,
// docs/particles.md): one invocation per candidate of one stream (the
// rate's birth window, or a burst), writing its record whether alive or
// not (a dead one gets size 0 and draws nothing), so the records' order is
// the candidates' and a frame's bits do not depend on scheduling.
//
// Birth times and ages are double (scene times of hours keep their
// microseconds, as on the CPU); the motion is float, emitter-relative.
layout(local_size_x = 64) in;

struct PackedParticle {
  vec4 positionSize;      // relative to the frame origin; size in metres
  vec4 colour;            // linear RGB, opacity
  vec4 velocityRotation;  // m/s; rotation in degrees
  uvec4 frameVariant;     // flipbook frame, variant bits, 0, 0
};
layout(std430, binding = 0) writeonly buffer Particles { PackedParticle outParticles[]; };
// Per rate boundary: scene time, rate, N (SpawnSchedule).
layout(std430, binding = 1) readonly buffer Schedule { double schedule[]; };
// Size keys (t, value, 0, 0), then colour keys as pairs (t, 0, 0, 0), (r, g, b, a).
layout(std430, binding = 2) readonly buffer Curves { vec4 curves[]; };

uniform double t;             // scene time
uniform double burstTime;     // the burst's time (stream > 0)
uniform uint seed;
uniform uint stream;          // 0: the rate; b + 1: burst b
uniform uvec2 indexBase;      // the first candidate's index (low, high word)
uniform uint count;           // candidates of this dispatch
uniform uint outBase;         // its first record
uniform int boundaries;       // of the schedule
uniform uint shape;           // particles::Shape: 0 point, 1 box, 2 sphere, 3 disc, 4 cone
uniform bool surfaceOnly;
uniform bool alongNormal;
uniform vec3 direction;       // unit
uniform float spreadRad;
uniform vec3 boxHalf;
uniform float radius;
uniform float coneRad;
uniform vec2 speed, lifetime, size, rotationDeg, spinDegPerS;  // MIN, MAX
uniform vec3 gravity;
uniform float drag;
uniform vec3 wind;
uniform int flipbookFrames;
uniform int sizeKeys, colourKeys;
uniform vec3 offset;          // the emitter's origin minus the frame origin (formed in double on the CPU)

const float kPi = 3.14159265358979;

uint hsHash(uint x) {
  x ^= x >> 16; x *= 0x7feb352dU;
  x ^= x >> 15; x *= 0x846ca68bU;
  x ^= x >> 16; return x;
}
uint hsKey(uint s, uint st, uint index, uint attr) { return hsHash(hsHash(hsHash(hsHash(s) ^ st) ^ index) ^ attr); }
float hsUnit(uint h) { return float(h >> 8) * (1.0 / 16777216.0); }

// particles/rng.h's attributes.
const uint kBirthJitter = 1u, kLifetime = 2u, kSpeed = 3u, kSpreadA = 4u, kSpreadB = 5u, kShapeA = 6u,
           kShapeB = 7u, kShapeC = 8u, kSize = 9u, kRotation = 10u, kSpin = 11u, kVariant = 12u;

// N^-1(n) of the piecewise-linear rate (SpawnSchedule::invert): the same
// segment choice and cancellation-free root, in double.
double invertSchedule(double n) {
  if (n <= 0.0) return schedule[0];
  int i = 0;  // the last boundary with N <= n
  while (i + 1 < boundaries && schedule[3 * (i + 1) + 2] <= n) ++i;
  if (i >= boundaries - 1) {
    i = boundaries - 2;
    while (i > 0 && schedule[3 * i + 2] >= n) --i;
  }
  double a0 = schedule[3 * i], len = schedule[3 * (i + 1)] - a0;
  double r0 = schedule[3 * i + 1], s = (schedule[3 * (i + 1) + 1] - r0) / len, d = n - schedule[3 * i + 2];
  double disc = max(0.0, r0 * r0 + 2.0 * s * d);
  double den = r0 + sqrt(disc);
  double x = den > 0.0 ? 2.0 * d / den : 0.0;
  return a0 + clamp(x, 0.0, len);
}

// phi1(z) = (1 - e^-z) / z and phi2(z) = (z - 1 + e^-z) / z^2 (motion.h),
// with series where the closed forms cancel in float.
float phi1(float z) {
  if (z < 1e-3) return 1.0 - z * (0.5 - z * (1.0 / 6.0 - z / 24.0));
  return (1.0 - exp(-z)) / z;
}
float phi2(float z) {
  if (z < 0.25) {
    float r = 0.0, term = 1.0;
    const float c[8] = float[](1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0, 1.0 / 720.0, 1.0 / 5040.0,
                               1.0 / 40320.0, 1.0 / 362880.0);
    for (int k = 0; k < 8; ++k) {
      r += c[k] * term;
      term *= -z;
    }
    return r;
  }
  return (z - 1.0 + exp(-z)) / (z * z);
}

void basis(vec3 a, out vec3 b1, out vec3 b2) {
  vec3 h = abs(a.z) < 0.9 ? vec3(0, 0, 1) : vec3(1, 0, 0);
  b1 = normalize(cross(h, a));
  b2 = cross(a, b1);
}

float curveSize(float x) {
  if (sizeKeys == 0) return 1.0;
  if (x <= curves[0].x) return curves[0].y;
  for (int k = 1; k < sizeKeys; ++k)
    if (x < curves[k].x) {
      vec4 a = curves[k - 1], b = curves[k];
      return a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x));
    }
  return curves[sizeKeys - 1].y;
}

vec4 curveColour(float x) {
  if (colourKeys == 0) return vec4(1.0);
  int base = sizeKeys;
  if (x <= curves[base].x) return curves[base + 1];
  for (int k = 1; k < colourKeys; ++k) {
    int at = base + 2 * k;
    if (x < curves[at].x) {
      float a = curves[at - 2].x, b = curves[at].x;
      return mix(curves[at - 1], curves[at + 1], (x - a) / (b - a));
    }
  }
  return curves[base + 2 * colourKeys - 1];
}

float unitOf(uint rngStream, uint index, uint attr) { return hsUnit(hsKey(seed, rngStream, index, attr)); }
float rangeOf(uint rngStream, uint index, uint attr, vec2 r) { return r.x + (r.y - r.x) * unitOf(rngStream, index, attr); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  // The candidate's index: indexBase + i, 64 bits in two words.
  uint lo = indexBase.x + i;
  uint hi = indexBase.y + (lo < indexBase.x ? 1u : 0u);
  uint rs = stream ^ (hi * 0x9e3779b9U);  // particles::rngOf
  double birth = burstTime;
  if (stream == 0u) {
    double k = double(hi) * 4294967296.0 + double(lo);
    birth = invertSchedule(k + double(unitOf(hi * 0x9e3779b9U, lo, kBirthJitter)));
  }
  float life = rangeOf(rs, lo, kLifetime, lifetime);
  double ageD = t - birth;
  PackedParticle q;
  q.positionSize = vec4(0.0);
  q.colour = vec4(0.0);
  q.velocityRotation = vec4(0.0);
  q.frameVariant = uvec4(0u);
  if (!(ageD >= 0.0) || !(ageD < double(life))) {  // not born yet, or dead: draws nothing
    outParticles[outBase + i] = q;
    return;
  }
  float age = float(ageD);

  // Where and how it starts (Evaluator::startAt).
  float a = unitOf(rs, lo, kShapeA), b = unitOf(rs, lo, kShapeB), c = unitOf(rs, lo, kShapeC);
  vec3 b1, b2;
  basis(direction, b1, b2);
  vec3 pos = vec3(0.0), normal = direction, base = direction;
  if (shape == 1u) {
    pos = (2.0 * vec3(a, b, c) - 1.0) * boxHalf;
  } else if (shape == 2u) {
    float z = 2.0 * a - 1.0, phi = 2.0 * kPi * b, rr = sqrt(max(0.0, 1.0 - z * z));
    normal = vec3(rr * cos(phi), rr * sin(phi), z);
    pos = normal * (radius * (surfaceOnly ? 1.0 : pow(c, 1.0 / 3.0)));
  } else if (shape == 3u || shape == 4u) {
    float rho = surfaceOnly ? 1.0 : sqrt(a), phi = 2.0 * kPi * b;
    vec3 radial = cos(phi) * b1 + sin(phi) * b2;
    pos = radial * (radius * rho);
    if (shape == 4u) {
      float lean = coneRad * rho;
      base = normal = cos(lean) * direction + sin(lean) * radial;
    }
  }
  if (alongNormal) base = normal;
  vec3 dir = base;
  if (spreadRad > 0.0) {
    // ct = 1 - u (1 - cos spread), as on the CPU; in float 1 - ct^2 would
    // cancel near the axis, so the sine comes from w = 1 - ct itself.
    float sh = sin(0.5 * spreadRad);
    float w = unitOf(rs, lo, kSpreadA) * (2.0 * sh * sh);
    float ct = 1.0 - w, st = sqrt(max(0.0, w * (2.0 - w)));
    float phi = 2.0 * kPi * unitOf(rs, lo, kSpreadB);
    vec3 c1, c2;
    basis(base, c1, c2);
    dir = ct * base + st * (cos(phi) * c1 + sin(phi) * c2);
  }
  vec3 v0 = dir * rangeOf(rs, lo, kSpeed, speed);

  // The exact motion under gravity, drag and constant wind (motion.h).
  float z = drag * age;
  vec3 a0 = gravity + drag * (wind - v0);
  vec3 v = v0 + a0 * (age * phi1(z));
  vec3 x = pos + v0 * age + a0 * (age * age * phi2(z));

  float lifeX = life > 0.0 ? clamp(age / life, 0.0, 1.0) : 0.0;
  float sz = rangeOf(rs, lo, kSize, size) * curveSize(lifeX);
  float rot = rangeOf(rs, lo, kRotation, rotationDeg) + rangeOf(rs, lo, kSpin, spinDegPerS) * max(0.0, age);
  q.positionSize = vec4(offset + x, sz);
  q.colour = curveColour(lifeX);
  q.velocityRotation = vec4(v, rot);
  q.frameVariant = uvec4(uint(min(flipbookFrames - 1, int(lifeX * float(flipbookFrames)))),
                         hsKey(seed, rs, lo, kVariant), 0u, 0u);
  outParticles[outBase + i] = q;
}
