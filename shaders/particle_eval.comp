#version 450 core
// GPU evaluation of an emitter (render/particle_gpu_eval.h): one
// invocation per candidate of the live window at scene time t, the same
// arithmetic as particles::Evaluator (docs/particles.md): the
// counter-based hash for every random number (same bits as the CPU), birth
// times from the rate's exact inverse, the start (shape, spread, speed),
// the exact motion under gravity, drag and constant wind, with turbulence
// the fixed-step replay from the birth (the CPU's grid and midpoint rule,
// the same curl noise), the life curves and the flipbook frame; written as
// particles::PackedParticle records relative to the frame origin. Double
// precision throughout the motion (GLSL has no double exp: expD below);
// float only inside the start's sin, cos and pow.
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
// The terrain's samples, row by row, relative to its origin's z; NaN where
// a sample is a hole (bound only for an emitter that collides with it).
layout(std430, binding = 3) readonly buffer TerrainHeights { float th[]; };
uniform uint uFirst;  // the first record written
uniform uint uCount;  // candidates

// Slots of d[] (keep in step with particle_gpu_eval.cpp).
const int D_OFFSET = 0, D_T = 3, D_LIFE = 4, D_SIZE = 6, D_ROT = 8, D_SPIN = 10, D_SPEED = 12, D_DIR = 14,
          D_SPREAD = 17, D_BOX = 18, D_RADIUS = 21, D_CONE = 22, D_GRAVITY = 23, D_DRAG = 26, D_WIND = 27,
          D_SEGMENTS = 32, MAX_SEGMENTS = 64, D_SIZE_KEYS = 224, MAX_KEYS = 16, D_COLOUR_KEYS = 256,
          D_BURST_BIRTH = 352, D_TURBULENCE = 417, D_STEP = 420, D_ORIGIN = 421, D_TERRAIN = 424, D_COLLIDE = 430;
// Slots of u[].
const int U_SEED = 0, U_SHAPE = 1, U_SURFACE_ONLY = 2, U_ALONG_NORMAL = 3, U_FLIPBOOK = 4, U_SIZE_KEYS = 5,
          U_COLOUR_KEYS = 6, U_RANGES = 7, U_PACK_SEED = 8, U_SEGMENTS = 9, U_REPLAY = 10, U_COLLIDE = 11,
          U_TERRAIN_NX = 12, U_TERRAIN_NY = 13, U_RANGE0 = 16;
// particles::CollisionMode, particles::Fate; evaluate.cpp's kSkin and kMaxContactsPerStep.
const uint C_NONE = 0u, C_BOUNCE = 1u, C_KILL = 2u, C_STICK = 3u;
const uint F_FLYING = 0u, F_RESTING = 1u, F_KILLED = 2u;
const double kSkin = 1e-5LF;
const int kMaxContactsPerStep = 8;
// particles::Attr.
const uint A_JITTER = 1u, A_LIFETIME = 2u, A_SPEED = 3u, A_SPREAD_A = 4u, A_SPREAD_B = 5u, A_SHAPE_A = 6u,
           A_SHAPE_B = 7u, A_SHAPE_C = 8u, A_SIZE = 9u, A_ROTATION = 10u, A_SPIN = 11u, A_VARIANT = 12u;
const double PI = 3.14159265358979323846LF;

#include "lowbias32.glsl"  // as particles/rng.h
uint hsKey(uint seed, uint stream, uint index, uint attr) {
  return lowbias32(lowbias32(lowbias32(lowbias32(seed) ^ stream) ^ index) ^ attr);
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

// exp in double for x <= 0 (GLSL has none): Cody-Waite reduction to
// |r| <= ln2 / 2 and the Taylor series to r^13 (relative error ~1e-16),
// so the motion keeps the CPU's doubles step after step of a replay.
double expD(double x) {
  if (x < -745.0LF) return 0.0LF;
  const double n = floor(x * 1.4426950408889634LF + 0.5LF);
  const double r = (x - n * 0.693147180369123816490LF) - n * 1.90821492927058770002e-10LF;
  double p = 1.0LF;
  for (int k = 13; k >= 1; --k) p = 1.0LF + r * p / double(k);
  return ldexp(p, int(n));
}

// phi1, phi2 (motion.cpp): series below z = 0.25, the closed form above.
double phi1(double z) {
  if (z < 0.25LF) {
    double r = 0.0LF, f = 1.0LF;
    double c[15];
    for (int n = 0; n < 15; ++n) { f *= double(n + 1); c[n] = 1.0LF / f; }  // 1/(n+1)!
    for (int n = 14; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (1.0LF - expD(-z)) / z;
}
double phi2(double z) {
  if (z < 0.25LF) {
    double r = 0.0LF, f = 1.0LF;
    double c[14];
    for (int n = 0; n < 14; ++n) { f *= double(n + 2); c[n] = 1.0LF / f; }  // 1/(n+2)!
    for (int n = 13; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (z - 1.0LF + expD(-z)) / (z * z);
}

// motion.cpp exactMotion: (x, v) after tau under `gravity`, the drag and the constant wind.
void exactMotion(inout dvec3 x, inout dvec3 v, dvec3 gravity, double tau) {
  const double k = d[D_DRAG];
  const double z = k * tau;
  const dvec3 a0 = gravity + k * (d3(D_WIND) - v);
  x = x + v * tau + a0 * (tau * tau * phi2(z));
  v = v + a0 * (tau * phi1(z));
}

// noise.cpp: gradient noise's gradient and the curl of three potentials.
const dvec3 kCorner[12] = dvec3[12](dvec3(1, 1, 0), dvec3(-1, 1, 0), dvec3(1, -1, 0), dvec3(-1, -1, 0),
                                    dvec3(1, 0, 1), dvec3(-1, 0, 1), dvec3(1, 0, -1), dvec3(-1, 0, -1),
                                    dvec3(0, 1, 1), dvec3(0, -1, 1), dvec3(0, 1, -1), dvec3(0, -1, -1));
dvec3 cornerGradient(uint ix, uint iy, uint iz, uint seed) {
  return kCorner[(lowbias32(lowbias32(lowbias32(lowbias32(seed) ^ ix) ^ iy) ^ iz) >> 8) % 12u];
}
uint lattice(double v) { return uint(v - 4294967296.0LF * floor(v / 4294967296.0LF)); }  // v mod 2^32, as int64 -> uint32
dvec3 noiseGradient(dvec3 p, uint seed) {
  const dvec3 fl = floor(p);
  const uint ix = lattice(fl.x), iy = lattice(fl.y), iz = lattice(fl.z);
  const dvec3 f = p - fl;
  const dvec3 uu = f * f * f * (f * (f * 6.0LF - 15.0LF) + 10.0LF);
  const dvec3 du = 30.0LF * f * f * (f * (f - 2.0LF) + 1.0LF);
  const dvec3 ga = cornerGradient(ix, iy, iz, seed), gb = cornerGradient(ix + 1u, iy, iz, seed),
              gc = cornerGradient(ix, iy + 1u, iz, seed), gd = cornerGradient(ix + 1u, iy + 1u, iz, seed),
              ge = cornerGradient(ix, iy, iz + 1u, seed), gf = cornerGradient(ix + 1u, iy, iz + 1u, seed),
              gg = cornerGradient(ix, iy + 1u, iz + 1u, seed), gh = cornerGradient(ix + 1u, iy + 1u, iz + 1u, seed);
  const double va = dot(ga, f), vb = dot(gb, f - dvec3(1, 0, 0)), vc = dot(gc, f - dvec3(0, 1, 0)),
               vd = dot(gd, f - dvec3(1, 1, 0)), ve = dot(ge, f - dvec3(0, 0, 1)), vf = dot(gf, f - dvec3(1, 0, 1)),
               vg = dot(gg, f - dvec3(0, 1, 1)), vh = dot(gh, f - dvec3(1, 1, 1));
  const double k1 = vb - va, k2 = vc - va, k3 = ve - va, k4 = va - vb - vc + vd, k5 = va - vc - ve + vg,
               k6 = va - vb - ve + vf, k7 = -va + vb + vc - vd + ve - vf - vg + vh;
  const dvec3 g0 = ga, g1 = gb - ga, g2 = gc - ga, g3 = ge - ga, g4 = ga - gb - gc + gd, g5 = ga - gc - ge + gg,
              g6 = ga - gb - ge + gf, g7 = -ga + gb + gc - gd + ge - gf - gg + gh;
  return g0 + g1 * uu.x + g2 * uu.y + g3 * uu.z + g4 * uu.x * uu.y + g5 * uu.y * uu.z + g6 * uu.z * uu.x +
         g7 * uu.x * uu.y * uu.z +
         du * dvec3(k1 + k4 * uu.y + k6 * uu.z + k7 * uu.y * uu.z, k2 + k5 * uu.z + k4 * uu.x + k7 * uu.z * uu.x,
                    k3 + k6 * uu.x + k5 * uu.y + k7 * uu.x * uu.y);
}
dvec3 turbulenceAt(dvec3 x, double t) {
  const uint seed = u[U_SEED];
  const dvec3 p = x * d[D_TURBULENCE + 1] + (t * d[D_TURBULENCE + 2]) * dvec3(0.37LF, 0.59LF, 0.71LF);
  const dvec3 d1 = noiseGradient(p, lowbias32(seed ^ 0x1u));
  const dvec3 d2 = noiseGradient(p, lowbias32(seed ^ 0x2u));
  const dvec3 d3v = noiseGradient(p, lowbias32(seed ^ 0x3u));
  return d[D_TURBULENCE] * dvec3(d3v.y - d2.z, d1.z - d3v.x, d2.x - d1.y);
}

// The terrain (foliage::terrainSurface over the samples, as scene::
// ParticleWorld's HeightFieldCollider reads them): the cell under a world
// XY, its triangle, the height and the normal there; false off the grid or
// over a hole.
bool terrainAt(dvec2 world, out double z, out dvec3 normal) {
  const int nx = int(u[U_TERRAIN_NX]), ny = int(u[U_TERRAIN_NY]);
  const dvec2 sp = dvec2(d[D_TERRAIN + 3], d[D_TERRAIN + 4]);
  const dvec2 s = (world - dvec2(d[D_TERRAIN], d[D_TERRAIN + 1])) / sp;
  if (!(s.x >= 0.0LF && s.y >= 0.0LF && s.x <= double(nx - 1) && s.y <= double(ny - 1))) return false;
  const int x0 = min(int(s.x), nx - 2), y0 = min(int(s.y), ny - 2);
  const double tx = s.x - double(x0), ty = s.y - double(y0);
  const float f00 = th[y0 * nx + x0], f10 = th[y0 * nx + x0 + 1], f01 = th[(y0 + 1) * nx + x0],
              f11 = th[(y0 + 1) * nx + x0 + 1];
  if (isnan(f00) || isnan(f10) || isnan(f01) || isnan(f11)) return false;  // Heightfield::cellIsHole
  const double v00 = double(f00), v10 = double(f10), v01 = double(f01), v11 = double(f11);
  double a = v00, dx, dy;
  if (tx >= ty) {
    dx = v10 - v00;
    dy = v11 - v10;
  } else {
    dx = v11 - v01;
    dy = v01 - v00;
  }
  z = d[D_TERRAIN + 2] + a + tx * dx + ty * dy;
  normal = normalize(normalize(dvec3(-dx / sp.x, -dy / sp.y, 1.0LF)));  // terrainSurface, then HeightFieldCollider::normal
  return true;
}
double terrainHeight(dvec2 world) {
  double z;
  dvec3 n;
  return terrainAt(world, z, n) ? z : -1e30LF;
}
dvec3 terrainNormal(dvec2 world) {
  double z;
  dvec3 n;
  return terrainAt(world, z, n) ? n : dvec3(0.0LF, 0.0LF, 1.0LF);
}

// HeightFieldCollider::raycast: samples every spacing metres along the
// segment, the first sign change of z - h bisected.
bool terrainRaycast(dvec3 from, dvec3 to, out dvec3 point, out dvec3 normal) {
  const dvec3 dd = to - from;
  const double f0 = from.z - terrainHeight(from.xy);
  if (f0 < 0.0LF) {
    point = dvec3(from.xy, terrainHeight(from.xy));
    normal = terrainNormal(from.xy);
    return true;
  }
  const double horizontal = sqrt(dd.x * dd.x + dd.y * dd.y);
  const int samples = int(min(1e6LF, ceil(horizontal / d[D_TERRAIN + 5]))) + 1;
  double s0 = 0.0LF, a0 = f0;
  for (int i = 1; i <= samples; ++i) {
    const double s1 = double(i) / double(samples);
    const dvec3 p1 = from + dd * s1;
    const double a1 = p1.z - terrainHeight(p1.xy);
    if (a1 < 0.0LF || (a1 == 0.0LF && a0 > 0.0LF)) {
      double lo = s0, hi = s1;
      const double len = length(dd);
      for (int it = 0; it < 60 && (hi - lo) * len > 1e-7LF; ++it) {
        const double m = 0.5LF * (lo + hi);
        const dvec3 pm = from + dd * m;
        if (pm.z - terrainHeight(pm.xy) > 0.0LF) lo = m;
        else hi = m;
      }
      const dvec3 p = from + dd * hi;
      point = dvec3(p.x, p.y, max(p.z, terrainHeight(p.xy)));
      normal = terrainNormal(p.xy);
      return true;
    }
    s0 = s1;
    a0 = a1;
  }
  return false;
}

// Evaluator::advance: one step of tau from scene time t0, the turbulence
// taken at the step's predicted midpoint (second order), a contact with
// the terrain located on the exact trajectory inside the step.
void advance(inout dvec3 x, inout dvec3 v, inout uint fate, inout double fateTime, double t0, double tau) {
  if (fate != F_FLYING || !(tau > 0.0LF)) return;
  dvec3 g = d3(D_GRAVITY);
  if (d[D_TURBULENCE] > 0.0LF) {
    dvec3 mx = x, mv = v;
    exactMotion(mx, mv, g, 0.5LF * tau);
    g += turbulenceAt(mx, t0 + 0.5LF * tau);
  }
  const uint mode = u[U_COLLIDE];
  const dvec3 origin = d3(D_ORIGIN);
  double remaining = tau, now = t0;
  for (int contact = 0; contact <= kMaxContactsPerStep; ++contact) {
    dvec3 nx = x, nv = v;
    exactMotion(nx, nv, g, remaining);
    dvec3 hitPoint, n;
    if (mode == C_NONE || !terrainRaycast(origin + x, origin + nx, hitPoint, n)) {
      x = nx;
      v = nv;
      return;
    }
    if (contact == kMaxContactsPerStep) break;
    // The hit time on the exact trajectory: where it crosses the tangent plane at the hit.
    const dvec3 P = hitPoint - origin;
    double lo = 0.0LF, hi = remaining;
    if (dot(x - P, n) <= 0.0LF) {
      hi = 0.0LF;
    } else {
      for (int it = 0; it < 64 && hi - lo > 1e-12LF * remaining; ++it) {
        const double m = 0.5LF * (lo + hi);
        dvec3 mx = x, mv = v;
        exactMotion(mx, mv, g, m);
        if (dot(mx - P, n) > 0.0LF) lo = m;
        else hi = m;
      }
    }
    dvec3 cx = x, cv = v;
    exactMotion(cx, cv, g, hi);
    cx += n * (kSkin - dot(cx - P, n));
    if (mode == C_KILL) {
      x = cx;
      v = cv;
      fate = F_KILLED;
      fateTime = now + hi;
      return;
    }
    if (mode == C_STICK) {
      x = cx;
      v = dvec3(0.0LF);
      fate = F_RESTING;
      fateTime = now + hi;
      return;
    }
    const double vn = dot(cv, n);  // bounce
    if (vn < 0.0LF) {
      const dvec3 vt = cv - vn * n;
      const double outSpeed = -d[D_COLLIDE] * vn;
      if (outSpeed < d[D_COLLIDE + 2]) {
        x = cx;
        v = dvec3(0.0LF);
        fate = F_RESTING;
        fateTime = now + hi;
        return;
      }
      cv = vt * (1.0LF - d[D_COLLIDE + 1]) + outSpeed * n;
    }
    x = cx;
    v = cv;
    remaining -= hi;
    now += hi;
    if (!(remaining > 0.0LF)) return;
  }
  // Contact after contact inside one step: resting contact.
  v = dvec3(0.0LF);
  fate = F_RESTING;
  fateTime = now;
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

  // The motion: closed form under constant forces, or with turbulence the
  // replay (Evaluator::replayTo): whole steps on the grid anchored at the
  // birth, then the remainder.
  dvec3 x = pos, v = v0;
  uint fate = F_FLYING;
  double fateTime = 0.0LF;
  if (u[U_REPLAY] == 0u) {
    exactMotion(x, v, d3(D_GRAVITY), age);
  } else {
    const double h = d[D_STEP];
    const double n = floor(age / h);
    for (double s = 0.0LF; s < n && fate == F_FLYING; s += 1.0LF) advance(x, v, fate, fateTime, birth + s * h, h);
    const double rem = age - n * h;
    if (rem > 0.0LF) advance(x, v, fate, fateTime, birth + n * h, rem);
  }
  if (fate == F_KILLED && fateTime <= t) {  // Evaluator::finish: killed by a collision
    q.position = vec3(0.0); q.size = 0.0; q.colour = vec4(0.0); q.velocity = vec3(0.0);
    q.rotationDeg = 0.0; q.frame = 0xFFFFFFFFu;
    particles[uFirst + i] = q;
    return;
  }

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
