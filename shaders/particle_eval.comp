#version 450 core
// GPU evaluation of an emitter without replay (render/particle_gpu_eval.h):
// one invocation per candidate of the live window at scene time t, the
// same arithmetic as particles::Evaluator (docs/particles.md): the
// counter-based hash for every random number (same bits as the CPU), birth
// times from the rate's exact inverse, the start (shape, spread, speed),
// the exact motion under gravity, drag and constant wind, the life curves
// and the flipbook frame; written as particles::PackedParticle records
// relative to the frame origin. Double precision where the CPU's doubles
// matter (births, positions); float only inside exp, sin, cos and pow.
// A candidate not alive at t (not yet born or past its lifetime) is
// written with size and opacity 0 (particle.vert draws nothing for it) and
// frame 0xFFFFFFFF.
layout(local_size_x = 64) in;

// Doubles (render/particle_gpu_eval.cpp, GpuEvalSlots).
layout(std430, binding = 0) readonly buffer EmitterDoubles { double d[]; };
// Integers: seed, shape, flags, counts, then the candidate ranges.
layout(std430, binding = 1) readonly buffer EmitterInts { uint u[]; };
struct PackedParticle {
  vec3 position;
  float size;
  vec4 colour;
  vec3 velocity;
  float rotationDeg;
  uint frame;
  uint variant;
  uint stream;  // the CPU record's padding: the particle's id, for tests
  uint index;
};
layout(std430, binding = 2) writeonly buffer Particles { PackedParticle particles[]; };
uniform uint uFirst;  // the first record written
uniform uint uCount;  // candidates

// Slots of d[] (keep in step with particle_gpu_eval.cpp).
const int D_OFFSET = 0, D_T = 3, D_LIFE = 4, D_SIZE = 6, D_ROT = 8, D_SPIN = 10, D_SPEED = 12, D_DIR = 14,
          D_SPREAD = 17, D_BOX = 18, D_RADIUS = 21, D_CONE = 22, D_GRAVITY = 23, D_DRAG = 26, D_WIND = 27,
          D_SEGMENTS = 32, MAX_SEGMENTS = 64, D_SIZE_KEYS = 224, MAX_KEYS = 16, D_COLOUR_KEYS = 256,
          D_BURST_BIRTH = 352;
// Slots of u[].
const int U_SEED = 0, U_SHAPE = 1, U_SURFACE_ONLY = 2, U_ALONG_NORMAL = 3, U_FLIPBOOK = 4, U_SIZE_KEYS = 5,
          U_COLOUR_KEYS = 6, U_RANGES = 7, U_PACK_SEED = 8, U_SEGMENTS = 9, U_RANGE0 = 16;
// particles::Attr.
const uint A_JITTER = 1u, A_LIFETIME = 2u, A_SPEED = 3u, A_SPREAD_A = 4u, A_SPREAD_B = 5u, A_SHAPE_A = 6u,
           A_SHAPE_B = 7u, A_SHAPE_C = 8u, A_SIZE = 9u, A_ROTATION = 10u, A_SPIN = 11u, A_VARIANT = 12u;
const double PI = 3.14159265358979323846LF;

uint hsHash(uint x) {  // "lowbias32" (C. Wellons), as particles/rng.h
  x ^= x >> 16; x *= 0x7feb352dU;
  x ^= x >> 15; x *= 0x846ca68bU;
  x ^= x >> 16; return x;
}
uint hsKey(uint seed, uint stream, uint index, uint attr) {
  return hsHash(hsHash(hsHash(hsHash(seed) ^ stream) ^ index) ^ attr);
}
double hsUnit(uint h) { return double(h >> 8) * (1.0LF / 16777216.0LF); }

// A particle's random numbers: rngOf (evaluate.cpp) folds the index's high word into the stream.
uint gStream, gIndex;
double unit(uint attr) { return hsUnit(hsKey(u[U_SEED], gStream, gIndex, attr)); }
double range(uint attr, int slot) { return d[slot] + (d[slot + 1] - d[slot]) * unit(attr); }
dvec3 d3(int slot) { return dvec3(d[slot], d[slot + 1], d[slot + 2]); }

// SpawnSchedule::invert (spawn.cpp): the time N(t) reaches n.
double invertRate(double n) {
  const int m = int(u[U_SEGMENTS]);
  const int AT = D_SEGMENTS, RATE = D_SEGMENTS + MAX_SEGMENTS, CUM = D_SEGMENTS + 2 * MAX_SEGMENTS;
  if (n <= 0.0LF) return d[AT];
  int i = 0;  // the last boundary with cum <= n (upper_bound - 1)
  while (i + 1 < m && d[CUM + i + 1] <= n) ++i;
  if (i >= m - 1) {
    i = m - 2;
    while (i > 0 && d[CUM + i] >= n) --i;
  }
  const double len = d[AT + i + 1] - d[AT + i];
  const double r0 = d[RATE + i], s = (d[RATE + i + 1] - d[RATE + i]) / len, dn = n - d[CUM + i];
  const double disc = max(0.0LF, r0 * r0 + 2.0LF * s * dn);
  const double den = r0 + sqrt(disc);
  const double x = den > 0.0LF ? 2.0LF * dn / den : 0.0LF;
  return d[AT + i] + clamp(x, 0.0LF, len);
}

// phi1, phi2 (motion.cpp): series below z = 0.25 in double, the closed
// form above it with exp in float (its relative error there ~1e-6).
double phi1(double z) {
  if (z < 0.25LF) {
    double r = 0.0LF, f = 1.0LF;
    double c[15];
    for (int n = 0; n < 15; ++n) { f *= double(n + 1); c[n] = 1.0LF / f; }  // 1/(n+1)!
    for (int n = 14; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (1.0LF - double(exp(-float(z)))) / z;
}
double phi2(double z) {
  if (z < 0.25LF) {
    double r = 0.0LF, f = 1.0LF;
    double c[14];
    for (int n = 0; n < 14; ++n) { f *= double(n + 2); c[n] = 1.0LF / f; }  // 1/(n+2)!
    for (int n = 13; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (z - 1.0LF + double(exp(-float(z)))) / (z * z);
}

// evaluate.cpp basis(): two unit vectors across `a`.
void basis(dvec3 a, out dvec3 b1, out dvec3 b2) {
  const dvec3 h = abs(a.z) < 0.9LF ? dvec3(0, 0, 1) : dvec3(1, 0, 0);
  b1 = normalize(cross(h, a));
  b2 = cross(a, b1);
}

double curve(int slot, int keys, double x, double fallback) {
  if (keys == 0) return fallback;
  if (x <= d[slot]) return d[slot + 1];
  if (x >= d[slot + 2 * (keys - 1)]) return d[slot + 2 * (keys - 1) + 1];
  int i = 1;
  while (d[slot + 2 * i] <= x) ++i;  // upper_bound
  const double s = (x - d[slot + 2 * (i - 1)]) / (d[slot + 2 * i] - d[slot + 2 * (i - 1)]);
  return d[slot + 2 * (i - 1) + 1] + (d[slot + 2 * i + 1] - d[slot + 2 * (i - 1) + 1]) * s;
}
dvec4 colourCurve(int keys, double x) {
  const int S = D_COLOUR_KEYS;
  if (keys == 0) return dvec4(1.0LF);
  dvec4 first = dvec4(d[S + 1], d[S + 2], d[S + 3], d[S + 4]);
  const int l = S + 5 * (keys - 1);
  if (x <= d[S]) return first;
  if (x >= d[l]) return dvec4(d[l + 1], d[l + 2], d[l + 3], d[l + 4]);
  int i = 1;
  while (d[S + 5 * i] <= x) ++i;
  const int a = S + 5 * (i - 1), b = S + 5 * i;
  const double s = (x - d[a]) / (d[b] - d[a]);
  const dvec4 ca = dvec4(d[a + 1], d[a + 2], d[a + 3], d[a + 4]), cb = dvec4(d[b + 1], d[b + 2], d[b + 3], d[b + 4]);
  return ca + (cb - ca) * s;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  // Which range: the rate's window, then each burst in the window.
  uint r = 0u, rest = i;
  const uint ranges = u[U_RANGES];
  while (r + 1u < ranges && rest >= u[U_RANGE0 + 4u * r + 3u]) {
    rest -= u[U_RANGE0 + 4u * r + 3u];
    ++r;
  }
  const uint stream = u[U_RANGE0 + 4u * r];
  const uint lo = u[U_RANGE0 + 4u * r + 1u] + rest;
  const uint hi = u[U_RANGE0 + 4u * r + 2u] + (lo < rest ? 1u : 0u);  // the 64-bit index's carry
  gStream = stream ^ (hi * 0x9e3779b9U);
  gIndex = lo;

  double birth;
  if (stream == 0u) {
    // SpawnSchedule::birth: particle k is born when N(t) = k + its jitter.
    const double k = double(hi) * 4294967296.0LF + double(lo);
    const double jitter = hsUnit(hsKey(u[U_SEED], hi * 0x9e3779b9U, lo, A_JITTER));
    birth = invertRate(k + jitter);
  } else {
    birth = d[D_BURST_BIRTH + int(r)];
  }
  const double t = d[D_T];
  const double lifetime = range(A_LIFETIME, D_LIFE);
  const double age = t - birth;
  PackedParticle q;
  q.stream = stream;
  q.index = lo;
  q.variant = hsKey(u[U_PACK_SEED], gStream, gIndex, A_VARIANT);
  if (!(age >= 0.0LF && age < lifetime)) {
    q.position = vec3(0.0); q.size = 0.0; q.colour = vec4(0.0); q.velocity = vec3(0.0);
    q.rotationDeg = 0.0; q.frame = 0xFFFFFFFFu;  // not alive
    particles[uFirst + i] = q;
    return;
  }
  const double size = range(A_SIZE, D_SIZE);
  const double rotation = range(A_ROTATION, D_ROT), spin = range(A_SPIN, D_SPIN);

  // The start (Evaluator::startAt).
  const double a = unit(A_SHAPE_A), b = unit(A_SHAPE_B), c = unit(A_SHAPE_C);
  const dvec3 axis = d3(D_DIR);
  dvec3 b1, b2;
  basis(axis, b1, b2);
  dvec3 pos = dvec3(0.0LF), normal = axis, base = axis;
  const uint shape = u[U_SHAPE];
  const bool surfaceOnly = u[U_SURFACE_ONLY] != 0u;
  if (shape == 1u) {  // box
    pos = (2.0LF * dvec3(a, b, c) - 1.0LF) * d3(D_BOX);
  } else if (shape == 2u) {  // sphere
    const double z = 2.0LF * a - 1.0LF, phi = 2.0LF * PI * b, rr = sqrt(max(0.0LF, 1.0LF - z * z));
    normal = dvec3(rr * double(cos(float(phi))), rr * double(sin(float(phi))), z);
    pos = normal * (d[D_RADIUS] * (surfaceOnly ? 1.0LF : double(pow(float(c), 1.0 / 3.0))));
  } else if (shape == 3u || shape == 4u) {  // disc, cone
    const double rho = surfaceOnly ? 1.0LF : sqrt(a), phi = 2.0LF * PI * b;
    const dvec3 radial = double(cos(float(phi))) * b1 + double(sin(float(phi))) * b2;
    pos = radial * (d[D_RADIUS] * rho);
    if (shape == 4u) {
      const double lean = d[D_CONE] * PI / 180.0LF * rho;
      base = normal = double(cos(float(lean))) * axis + double(sin(float(lean))) * radial;
    }
  }
  if (u[U_ALONG_NORMAL] != 0u) base = normal;
  dvec3 dir = base;
  if (d[D_SPREAD] > 0.0LF) {
    const double cosMax = double(cos(float(d[D_SPREAD] * PI / 180.0LF)));
    const double ct = 1.0LF - unit(A_SPREAD_A) * (1.0LF - cosMax), st = sqrt(max(0.0LF, 1.0LF - ct * ct));
    const double phi = 2.0LF * PI * unit(A_SPREAD_B);
    dvec3 c1, c2;
    basis(base, c1, c2);
    dir = ct * base + st * (double(cos(float(phi))) * c1 + double(sin(float(phi))) * c2);
  }
  const dvec3 v0 = dir * range(A_SPEED, D_SPEED);

  // The exact motion (motion.cpp exactMotion) under constant forces.
  const double k = d[D_DRAG];
  const double z = k * age;
  const dvec3 a0 = d3(D_GRAVITY) + k * (d3(D_WIND) - v0);
  const dvec3 v = v0 + a0 * (age * phi1(z));
  const dvec3 x = pos + v0 * age + a0 * (age * age * phi2(z));

  // Evaluator::finish and packFrame.
  const double life = lifetime > 0.0LF ? clamp(age / lifetime, 0.0LF, 1.0LF) : 0.0LF;
  const int frames = int(u[U_FLIPBOOK]);
  q.position = vec3(d3(D_OFFSET) + x);
  q.velocity = vec3(v);
  q.size = float(size * curve(D_SIZE_KEYS, int(u[U_SIZE_KEYS]), life, 1.0LF));
  q.colour = vec4(colourCurve(int(u[U_COLOUR_KEYS]), life));
  q.rotationDeg = float(rotation + spin * max(0.0LF, age));
  q.frame = uint(min(frames - 1, int(life * double(frames))));
  particles[uFirst + i] = q;
}
