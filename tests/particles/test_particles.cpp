// Particles: the exact motion against a fine RK4 reference and at stiff
// extremes, birth-time inversion against brute-force counts, determinism
// (cold and warm replay, a frame alone and after a sequence, any thread
// count), collision (penetration, restitution 0 and 1), bad input, UTM
// coordinates, JSON round trips.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <numbers>

#include <glm/geometric.hpp>

#include "particles/bounds.h"
#include "particles/emitter.h"
#include "particles/evaluate.h"
#include "particles/motion.h"
#include "particles/noise.h"
#include "particles/presets.h"
#include "particles/rng.h"
#include "particles/spawn.h"
#include "particles/sprites.h"

using namespace hs::particles;
using glm::dvec3;

namespace {

// phi2 in long double: the closed form where it does not cancel, else its series.
long double phi2Ref(long double z) {
  if (z > 1e-2L) return (z + std::expm1(-z)) / (z * z);
  long double sum = 0, term = 0.5L;
  for (int n = 0; n < 30; ++n) {
    sum += term;
    term *= -z / (long double)(n + 3);
  }
  return sum;
}

// x(tau) of the exact solution, in long double, written the textbook way
// where that is accurate (k tau not small) and by series where it is not.
dvec3 exactRefX(const Kinematics& s, const Forces& f, double tau) {
  dvec3 out;
  for (int i = 0; i < 3; ++i) {
    const long double k = f.drag, t = tau, v0 = s.v[i], a0 = (long double)f.gravity[i] + k * ((long double)f.wind[i] - v0);
    out[i] = double((long double)s.x[i] + v0 * t + a0 * t * t * phi2Ref(k * t));
  }
  return out;
}

double maxAbs(const dvec3& a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }

bool finite(const dvec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

bool sameBits(const Particle& a, const Particle& b) { return std::memcmp(&a, &b, sizeof(Particle)) == 0 || a == b; }

EmitterDesc fountain() {
  EmitterDesc e;
  e.name = "Fountain";
  e.seed = 7;
  e.rate = 400;
  e.lifetimeMin = 2.0;
  e.lifetimeMax = 4.0;
  e.speedMin = 3.0;
  e.speedMax = 6.0;
  e.spreadDeg = 30;
  e.drag = 0.4;
  e.wind = {1.5, -0.5, 0.0};
  e.shape = Shape::Disc;
  e.radius = 0.5;
  e.origin = {0, 0, 2};
  return e;
}

// Hills: z = 0.3 sin(0.7 x) cos(0.5 y) + 0.1 x (world coordinates around `at`).
HeightFieldCollider hills(dvec3 at = dvec3(0.0)) {
  return HeightFieldCollider([at](double x, double y) {
    const double u = x - at.x, v = y - at.y;
    return at.z + 0.3 * std::sin(0.7 * u) * std::cos(0.5 * v) + 0.1 * u;
  });
}

}  // namespace

class TestParticles : public QObject {
  Q_OBJECT

 private slots:
  void rngIsUniformAndFloatExact() {
    double sum = 0, sum2 = 0;
    const int n = 200000;
    int floatExact = 0;
    for (int i = 0; i < n; ++i) {
      const double u = unitFromHash(hashKey(3, 0, uint32_t(i), 1));
      QVERIFY(u >= 0.0 && u < 1.0);
      sum += u;
      sum2 += u * u;
      floatExact += double(float(u)) == u;
    }
    const double mean = sum / n, var = sum2 / n - mean * mean;
    qInfo("hash unit: mean %.5f variance %.5f over %d", mean, var, n);
    QVERIFY(std::abs(mean - 0.5) < 0.003);
    QVERIFY(std::abs(var - 1.0 / 12.0) < 0.002);
    QCOMPARE(floatExact, n);
    // Neighbouring counters are not correlated (lag-1 correlation).
    double c = 0;
    for (int i = 0; i + 1 < n; ++i)
      c += (unitFromHash(hashKey(3, 0, uint32_t(i), 1)) - 0.5) * (unitFromHash(hashKey(3, 0, uint32_t(i + 1), 1)) - 0.5);
    QVERIFY(std::abs(c / n * 12.0) < 0.01);
  }

  void phiFunctionsAccurateForEveryZ() {
    double worst1 = 0, worst2 = 0;
    for (double lz = -15; lz <= 7; lz += 0.01) {
      const double z = std::pow(10.0, lz);
      const long double r1 = z > 1e-3 ? -std::expm1(-(long double)z) / (long double)z
                                      : 1.0L - z / 2.0L + (long double)z * z / 6.0L - (long double)z * z * z / 24.0L;
      worst1 = std::max(worst1, double(std::abs((phi1(z) - r1) / r1)));
      const long double r2 = phi2Ref(z);
      worst2 = std::max(worst2, double(std::abs((phi2(z) - r2) / r2)));
    }
    qInfo("phi1 worst relative error %.3g, phi2 %.3g (z from 1e-15 to 1e7)", worst1, worst2);
    QVERIFY(worst1 < 1e-14);
    QVERIFY(worst2 < 1e-14);
    QCOMPARE(phi1(0.0), 1.0);
    QCOMPARE(phi2(0.0), 0.5);
  }

  void exactMatchesFineRk4() {
    const Kinematics s0{{1, 2, 3}, {4, -2, 7}};
    for (double k : {0.0, 1e-12, 0.01, 0.5, 3.0, 40.0}) {
      const Forces f{{0, 0, -9.81}, k, {2, 1, 0}};
      const double T = 2.5, h = 1e-4;
      const Kinematics ref = integrate(Integrator::Rk4, s0, f, T, h);
      const Kinematics ex = exactMotion(s0, f, T);
      const double ex_err = maxAbs(ex.x - ref.x), ev_err = maxAbs(ex.v - ref.v);
      qInfo("k = %g: |x - rk4| %.3g m, |v - rk4| %.3g m/s", k, ex_err, ev_err);
      QVERIFY2(ex_err < 1e-9 && ev_err < 1e-9, qPrintable(QString("k = %1").arg(k)));
    }
  }

  void exactIsStableOnStiffAndVanishingDrag() {
    const Kinematics s0{{0, 0, 100}, {30, 0, 20}};
    const dvec3 g{0, 0, -9.81}, w{3, 4, 0};
    // k dt = 1e6: at terminal velocity, finite, and on the long-double reference.
    for (double k : {1e4, 1e6, 1e7}) {
      const Forces f{g, k, w};
      const double tau = 1e6 / k;
      const Kinematics r = exactMotion(s0, f, tau);
      QVERIFY(finite(r.x) && finite(r.v));
      const dvec3 vt = w + g / k;
      QVERIFY2(maxAbs(r.v - vt) <= 1e-12 * (1 + maxAbs(vt)), qPrintable(QString("k = %1").arg(k)));
      const double e = maxAbs(r.x - exactRefX(s0, f, tau));
      qInfo("k = %g, k tau = 1e6: |x - reference| %.3g m", k, e);
      QVERIFY(e < 1e-9);
      // Explicit Euler at the same step blows up; the exact update does not.
      const Kinematics eu = eulerStep(s0, f, tau);
      QVERIFY(maxAbs(eu.v) > 1e3);
    }
    // k = 1e-12 and 0: ballistic to 1e-9.
    for (double k : {0.0, 1e-12}) {
      const Forces f{g, k, w};
      const double tau = 10.0;
      const Kinematics r = exactMotion(s0, f, tau);
      const dvec3 ball = s0.x + s0.v * tau + 0.5 * g * tau * tau;
      const double e = maxAbs(r.x - ball), er = maxAbs(r.x - exactRefX(s0, f, tau));
      qInfo("k = %g: |x - ballistic| %.3g m, |x - reference| %.3g m", k, e, er);
      // k = 1e-12 really drags: k |w - v| tau^2 / 2 = 1.5e-9 m here.
      QVERIFY(e < 1e-8 && er < 1e-9);
    }
    // Tiny steps: no cancellation.
    const Forces f{g, 5.0, w};
    for (double tau : {1e-12, 1e-9, 1e-6}) {
      const Kinematics r = exactMotion(s0, f, tau);
      const double e = maxAbs(r.x - exactRefX(s0, f, tau));
      QVERIFY2(e < 1e-13, qPrintable(QString("tau %1: %2").arg(tau).arg(e)));
    }
  }

  void keyedWindIsExactToo() {
    // Wind keyed over time against RK4 with a tiny step on the same w(t).
    const std::vector<WindKey> keys = {{1.0, {0, 0, 0}}, {1.7, {6, -2, 1}}, {2.2, {6, -2, 1}}, {3.5, {-4, 3, 0}}};
    const Kinematics s0{{1, 2, 3}, {4, -2, 7}};
    const double t0 = 0.6, T = 3.6;  // from before the first key to after the last
    QCOMPARE(phi3(0.0), 1.0 / 6.0);
    double worst3 = 0;
    for (double lz = -12; lz <= 6; lz += 0.01) {
      const long double z = std::pow(10.0L, (long double)lz);
      long double ref = 0, term = 1.0L / 6.0L;
      if (z > 0.5L) {
        ref = (z * z / 2 - z - std::expm1(-z)) / (z * z * z);
      } else {
        for (int n = 0; n < 40; ++n) ref += term, term *= -z / (long double)(n + 4);
      }
      worst3 = std::max(worst3, double(std::abs((phi3(double(z)) - ref) / ref)));
    }
    qInfo("phi3 worst relative error %.3g", worst3);
    QVERIFY(worst3 < 1e-13);
    for (double k : {0.0, 1e-9, 0.7, 9.0, 60.0}) {
      const Forces f{{0, 0, -9.81}, k, {9, 9, 9}};  // f.wind is not used with keys
      auto acc = [&](double t, const dvec3& v) { return f.gravity + k * (windAt(keys, t, f.wind) - v); };
      Kinematics r = s0;
      const int n = 360000;
      const double h = T / n;
      for (int i = 0; i < n; ++i) {
        const double t = t0 + i * h;
        const dvec3 k1x = r.v, k1v = acc(t, r.v);
        const dvec3 k2x = r.v + 0.5 * h * k1v, k2v = acc(t + 0.5 * h, k2x);
        const dvec3 k3x = r.v + 0.5 * h * k2v, k3v = acc(t + 0.5 * h, k3x);
        const dvec3 k4x = r.v + h * k3v, k4v = acc(t + h, k4x);
        r.x += h / 6 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        r.v += h / 6 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      }
      const Kinematics ex = exactMotionKeyed(s0, f, keys, t0, T);
      const double ex_err = maxAbs(ex.x - r.x), ev_err = maxAbs(ex.v - r.v);
      qInfo("keyed wind, k = %g: |x - rk4| %.3g m, |v - rk4| %.3g m/s", k, ex_err, ev_err);
      QVERIFY2(ex_err < 1e-8 && ev_err < 1e-8, qPrintable(QString("k = %1").arg(k)));
      // Split anywhere: the same to rounding (the evaluator's replay steps split it).
      Kinematics split = exactMotionKeyed(s0, f, keys, t0, 1.3);
      split = exactMotionKeyed(split, f, keys, t0 + 1.3, T - 1.3);
      QVERIFY(maxAbs(split.x - ex.x) < 1e-11);
    }
    // Stiff with keys: finite, following the wind.
    const Forces stiff{{0, 0, -9.81}, 1e7, {0, 0, 0}};
    const Kinematics r = exactMotionKeyed(s0, stiff, keys, t0, T);
    QVERIFY(finite(r.x) && finite(r.v));
    QVERIFY(maxAbs(r.v - (windAt(keys, t0 + T, {}) + stiff.gravity / 1e7)) < 1e-5);
    // Through the emitter: JSON keeps the keys, validate() refuses coincident ones.
    EmitterDesc e = fountain();
    e.windKeys = keys;
    std::string err;
    const auto back = emitterFromJsonText(hs::writeJson(emitterToJson(e)), err);
    QVERIFY2(back && *back == e, err.c_str());
    e.windKeys[2].t = e.windKeys[1].t;
    QVERIFY(!validate(e).empty() && validate(e).front().find("wind_keys[2]") != std::string::npos);
  }

  void birthTimesInvertTheRateExactly() {
    EmitterDesc e;
    e.name = "Keyed";
    e.seed = 11;
    e.start = -0.5;
    e.duration = 5.0;
    e.rateKeys.keys = {{0.0, 0.0}, {1.0, 200.0}, {1.5, 200.0}, {3.0, 50.0}, {3.5, 0.0}, {3.8, 0.0}, {4.2, 900.0}};
    const SpawnSchedule s(e);
    // The integral against a fine numerical one (Simpson on the rate).
    auto numeric = [&](double t) {
      const int n = 200000;
      const double a = e.start, b = std::min(t, e.start + e.duration);
      if (b <= a) return 0.0;
      const double h = (b - a) / n;
      double sum = e.rateAt(a) + e.rateAt(b);
      for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * e.rateAt(a + i * h);
      return sum * h / 3.0;
    };
    for (double t : {-1.0, 0.3, 1.0, 1.2, 2.7, 3.6, 4.0, 4.5, 9.0}) {
      const double a = s.integral(t), b = numeric(t);
      QVERIFY2(std::abs(a - b) < 1e-3, qPrintable(QString("t %1: %2 vs %3").arg(t).arg(a).arg(b)));
    }
    // Every birth: in order, N(birth) = k + u_k, within the emission window.
    std::vector<double> births;
    for (uint64_t k = 0;; ++k) {
      const double b = s.birth(k);
      if (!std::isfinite(b)) break;
      births.push_back(b);
      QVERIFY(b >= e.start && b <= e.start + e.duration);
      QVERIFY(std::abs(s.integral(b) - (double(k) + s.jitter(k))) < 1e-9 * (1 + double(k)));
      if (k > 0) QVERIFY(b >= births[k - 1]);
      // Nobody is born while the rate is zero.
      QVERIFY2(!(b > 3.5 && b < 3.8) && b > 0.0, qPrintable(QString("birth %1 at %2").arg(k).arg(b)));
    }
    qInfo("%zu births, total N = %.3f", births.size(), s.total());
    QVERIFY(std::abs(double(births.size()) - s.total()) <= 1.0);
    // bornBy(t) is the brute-force count, at random times and at the births themselves.
    for (int i = 0; i < 3000; ++i) {
      const double t = -1.0 + 7.0 * unitFromHash(hashU32(uint32_t(i)));
      const uint64_t brute = uint64_t(std::upper_bound(births.begin(), births.end(), t) - births.begin());
      QCOMPARE(s.bornBy(t), brute);
    }
    for (size_t k = 0; k < births.size(); k += 7) {
      QCOMPARE(s.bornBy(births[k]), uint64_t(std::upper_bound(births.begin(), births.end(), births[k]) - births.begin()));
      QVERIFY(s.bornBy(births[k]) > k);
    }
  }

  void shapesPlaceParticlesWhereTheySay() {
    EmitterDesc e = fountain();
    e.spreadDeg = 0;
    e.direction = {0, 0, 1};
    std::string err;
    auto starts = [&](const EmitterDesc& x, const SurfaceSampler* surface = nullptr) {
      auto ev = Evaluator::create(x, {surface, {}}, err);
      std::vector<ParticleStart> v;
      if (!ev) return v;
      for (uint64_t k = 0; k < 2000; ++k) v.push_back(ev->start({0, k}));
      return v;
    };
    e.shape = Shape::Box;
    e.boxHalf = {1, 2, 3};
    dvec3 lo(1e9), hi(-1e9);
    for (const ParticleStart& s : starts(e)) lo = glm::min(lo, s.state.x), hi = glm::max(hi, s.state.x);
    QVERIFY(hi.x <= 1 && lo.x >= -1 && hi.y <= 2 && lo.y >= -2 && hi.z <= 3 && lo.z >= -3);
    QVERIFY(hi.x > 0.99 && lo.z < -2.99);  // fills it
    e.shape = Shape::Sphere;
    e.radius = 2.0;
    e.surfaceOnly = true;
    e.alongNormal = true;
    for (const ParticleStart& s : starts(e)) {
      QVERIFY(std::abs(glm::length(s.state.x) - 2.0) < 1e-12);
      QVERIFY(glm::dot(glm::normalize(s.state.x), glm::normalize(s.state.v)) > 1 - 1e-12);  // outwards
    }
    e.alongNormal = false;
    e.surfaceOnly = false;
    e.shape = Shape::Cone;
    e.radius = 1.0;
    e.coneAngleDeg = 30.0;
    for (const ParticleStart& s : starts(e)) {
      QVERIFY(std::abs(s.state.x.z) < 1e-12 && glm::length(s.state.x) <= 1.0 + 1e-12);
      const double lean = std::acos(glm::normalize(s.state.v).z) * 180.0 / std::numbers::pi;
      QVERIFY(std::abs(lean - 30.0 * glm::length(s.state.x)) < 1e-6);  // leans out with the distance from the axis
    }
    // A mesh: a tilted square of two triangles; births on it, velocities along its normal.
    const dvec3 a{0, 0, 0}, b{2, 0, 1}, c{2, 2, 1}, d{0, 2, 0};
    const TriangleSurface surface({a, b, c, a, c, d});
    e.shape = Shape::Mesh;
    e.mesh = "Roof";
    e.alongNormal = true;
    const dvec3 n = glm::normalize(glm::cross(b - a, d - a));
    int left = 0;
    for (const ParticleStart& s : starts(e, &surface)) {
      QVERIFY(std::abs(glm::dot(s.state.x - a, n)) < 1e-12);
      QVERIFY(s.state.x.y >= -1e-12 && s.state.x.y <= 2 + 1e-12 && s.state.x.x >= -1e-12 && s.state.x.x <= 2 + 1e-12);
      QVERIFY(glm::dot(glm::normalize(s.state.v), n) > 1 - 1e-12);
      left += s.state.x.y > s.state.x.x;
    }
    QVERIFY(left > 850 && left < 1150);  // area-weighted: half on each triangle
    QVERIFY(starts(e).empty());          // no surface: refused
    QVERIFY(err.find("'Roof' is missing") != std::string::npos);
    // Terrain: on the ground (hills at UTM coordinates) up to 0.5 m above it, inside the area.
    EmitterDesc t = fountain();
    t.origin = {500000.0, 4400000.0, 320.0};
    t.shape = Shape::Terrain;
    t.boxHalf = {20.0, 10.0, 0.5};
    t.alongNormal = true;
    t.spreadDeg = 0;
    const HeightFieldCollider ground = hills({500000.0, 4400000.0, 300.0});
    auto tev = Evaluator::create(t, {nullptr, {}}, err);
    QVERIFY(!tev && err.find("'terrain'") != std::string::npos);
    tev = Evaluator::create(t, {nullptr, {}, &ground}, err);
    QVERIFY2(tev, err.c_str());
    double lowest = 1e9, highest = -1e9;
    for (uint64_t k = 0; k < 2000; ++k) {
      const ParticleStart s = tev->start({0, k});
      const dvec3 w = t.origin + s.state.x;
      QVERIFY(std::abs(s.state.x.x) <= 20.0 && std::abs(s.state.x.y) <= 10.0);
      const double above = w.z - ground.height(w.x, w.y);
      lowest = std::min(lowest, above), highest = std::max(highest, above);
      QVERIFY(glm::dot(glm::normalize(s.state.v), ground.normal(w.x, w.y)) > 1 - 1e-9);
    }
    qInfo("terrain shape: births from %.3g to %.3g m above the ground", lowest, highest);
    QVERIFY(lowest >= -1e-9 && highest <= 0.5 + 1e-9 && highest > 0.45);
  }

  void exactFrameIsPureFunctionOfTime() {
    std::string err;
    auto ev = Evaluator::create(fountain(), {}, err);
    QVERIFY2(ev, err.c_str());
    QVERIFY(!ev->replays());
    const Frame f1 = ev->frame(7.25, nullptr, 1), f2 = ev->frame(7.25, nullptr, 0);
    QVERIFY(f1.particles.size() > 500);
    QCOMPARE(f1.particles.size(), f2.particles.size());
    for (size_t i = 0; i < f1.particles.size(); ++i) QVERIFY(sameBits(f1.particles[i], f2.particles[i]));
    // One particle alone equals the same particle in the frame.
    const Particle& p = f1.particles[f1.particles.size() / 2];
    QVERIFY(sameBits(ev->particle(p.id, 7.25), p));
    // Each particle on the exact solution from its start.
    const ParticleStart st = ev->start(p.id);
    const Kinematics k = exactMotion(st.state, {ev->desc().gravity, ev->desc().drag, ev->desc().wind}, 7.25 - st.birth);
    QCOMPARE(p.position, k.x);
    // Counted against the schedule: every candidate born in (t - 4, t] and alive by lifetime.
    uint64_t alive = 0;
    for (uint64_t i = ev->schedule().bornBy(7.25 - 4.0); i < ev->schedule().bornBy(7.25); ++i)
      alive += ev->particle({0, i}, 7.25).alive;
    QCOMPARE(uint64_t(f1.particles.size()), alive);
    // The counts without evaluation: live by lifetimes, candidates an upper bound; nothing before the start.
    QCOMPARE(ev->liveCount(7.25), alive);
    QVERIFY(ev->candidates(7.25) >= alive && ev->candidates(7.25) < alive * 2);
    EmitterDesc later = fountain();
    later.start = 100.0;
    later.duration = 10.0;
    auto lev = Evaluator::create(later, {}, err);
    QCOMPARE(lev->candidates(99.0), uint64_t(0));
    QVERIFY(lev->frame(99.0).particles.empty());
    QVERIFY(lev->candidates(105.0) > 0);
    QCOMPARE(lev->candidates(114.01), uint64_t(0));  // emission over and every lifetime (<= 4 s) past
  }

  void replayColdWarmAndSequenceAreBitIdentical() {
    EmitterDesc e = fountain();
    e.turbulence = 6.0;
    e.turbulenceFrequency = 0.8;
    e.collision = CollisionMode::Bounce;
    e.restitution = 0.5;
    e.friction = 0.2;
    e.restSpeed = 1.5;  // so that some come to rest
    e.replayStep = 1.0 / 97.0;  // not a divisor of the frame interval
    const HeightFieldCollider ground = hills();
    std::string err;
    auto ev = Evaluator::create(e, {nullptr, {&ground}}, err);
    QVERIFY2(ev, err.c_str());
    QVERIFY(ev->replays());
    const double fps = 60.0;
    const double t120 = 120.0 / fps;
    // Cold: frame 120 alone, no cache.
    const Frame cold = ev->frame(t120, nullptr, 1);
    // Warm: frames 100..119 into the cache, then 120, on two threads.
    ReplayCache cache;
    for (int f = 100; f < 120; ++f) ev->frame(f / fps, &cache, 2);
    const Frame warm = ev->frame(t120, &cache, 2);
    qInfo("frame 120: %zu particles; cold %llu replay steps, warm %llu; cache hits %llu misses %llu",
          cold.particles.size(), (unsigned long long)cold.replaySteps, (unsigned long long)warm.replaySteps,
          (unsigned long long)cache.hits, (unsigned long long)cache.misses);
    QVERIFY(cold.particles.size() > 300);
    QVERIFY(warm.replaySteps * 5 < cold.replaySteps);
    QCOMPARE(cold.particles.size(), warm.particles.size());
    int moved = 0;
    for (size_t i = 0; i < cold.particles.size(); ++i) {
      QVERIFY(sameBits(cold.particles[i], warm.particles[i]));
      moved += cold.particles[i].fate != Fate::Flying;
    }
    QVERIFY(moved > 0);  // some have touched the ground
    // Scrubbing backwards (cache ahead of t) replays from birth and still agrees.
    const Frame back = ev->frame(110 / fps, &cache, 1);
    const Frame backCold = ev->frame(110 / fps, nullptr, 2);
    QCOMPARE(back.particles.size(), backCold.particles.size());
    for (size_t i = 0; i < back.particles.size(); ++i) QVERIFY(sameBits(back.particles[i], backCold.particles[i]));
    // Single particles through the cache, in another order.
    ReplayCache c2;
    for (size_t i = cold.particles.size(); i-- > 0;) {
      const Particle& p = cold.particles[i];
      ev->particle(p.id, t120 - 0.3, &c2);
      QVERIFY(sameBits(ev->particle(p.id, t120, &c2), p));
    }
  }

  // World space: a particle starts at originAt(birth), relative to the
  // frame's origin; its motion after that is the local one shifted by it,
  // collisions meet the ground where the particle really is, the terrain
  // shape is placed around the birth-time origin, and local space ignores
  // originAt.
  void worldSpaceStartsWhereTheEmitterWasAtTheBirth() {
    auto originAt = [](double t) { return dvec3(500000.0 + 12.0 * t, 4400000.0 - 3.0 * t, 300.0 + 0.5 * t * t); };
    const double t = 3.0;
    EmitterDesc e = fountain();
    e.origin = originAt(t);
    std::string err;
    auto local = Evaluator::create(e, {}, err);
    e.space = Space::World;
    auto still = Evaluator::create(e, {}, err);
    EvaluatorInputs in;
    in.originAt = originAt;
    auto world = Evaluator::create(e, in, err);
    QVERIFY2(local && still && world, err.c_str());
    QVERIFY(world->movesInWorld() && !still->movesInWorld());
    const Frame fl = local->frame(t), fs = still->frame(t), fw = world->frame(t);
    QCOMPARE(fw.particles.size(), fl.particles.size());
    QVERIFY(fw.particles.size() > 100);
    double worst = 0.0;
    for (size_t i = 0; i < fw.particles.size(); ++i) {
      const Particle &a = fl.particles[i], &w = fw.particles[i];
      QVERIFY(sameBits(a, fs.particles[i]));  // world space on a still emitter is local space
      // The same motion, shifted by where the emitter was at the birth.
      const dvec3 shift = originAt(a.birth) - e.origin;
      worst = std::max(worst, maxAbs(w.position - (a.position + shift)));
      QVERIFY(w.velocity == a.velocity);
    }
    qInfo("world space: %zu particles, worst |x_world - (x_local + shift)| %.3g m", fw.particles.size(), worst);
    QVERIFY(worst < 1e-6);  // the shift is added at the birth, the motion is affine in it
    // The terrain shape: born on the ground around the birth-time origin.
    const HeightFieldCollider ground = hills(originAt(0.0));
    EmitterDesc terr = e;
    terr.shape = Shape::Terrain;
    terr.boxHalf = {5.0, 5.0, 0.0};
    terr.speedMin = terr.speedMax = 0.0;
    terr.gravity = dvec3(0.0);
    terr.drag = 0.0;
    EvaluatorInputs tin = in;
    tin.ground = &ground;
    auto tev = Evaluator::create(terr, tin, err);
    QVERIFY2(tev, err.c_str());
    for (const Particle& p : tev->frame(t).particles) {
      const dvec3 w = terr.origin + p.position, o = originAt(p.birth);
      QVERIFY(std::abs(w.x - o.x) <= 5.0 + 1e-6 && std::abs(w.y - o.y) <= 5.0 + 1e-6);
      QVERIFY(std::abs(w.z - ground.height(w.x, w.y)) < 1e-6);
    }
    // Colliding in world space: nobody ends below the ground (1 mm).
    EmitterDesc hit = e;
    hit.collision = CollisionMode::Stick;
    const HeightFieldCollider hillsHere = hills(originAt(0.0) - dvec3(0, 0, 4));
    EvaluatorInputs cin = in;
    cin.colliders = {&hillsHere};
    auto cev = Evaluator::create(hit, cin, err);
    QVERIFY2(cev, err.c_str());
    int stuck = 0;
    for (const Particle& p : cev->frame(t).particles) {
      const dvec3 w = hit.origin + p.position;
      QVERIFY(w.z > hillsHere.height(w.x, w.y) - 1e-3);
      stuck += p.fate == Fate::Resting;
    }
    QVERIFY(stuck > 0);
  }

  // The bound an out-of-view test uses holds every particle a brute-force
  // evaluation finds, over shapes, forces from none to stiff, turbulence,
  // keyed wind and bouncing collisions; and the curl noise stays under the
  // bound its construction gives.
  void boundsHoldEveryParticle() {
    double curlMax = 0.0;
    for (int i = 0; i < 200000; ++i) {
      const dvec3 p(0.37 * i, 0.011 * i * 1.3, -0.0071 * i);
      curlMax = std::max(curlMax, glm::length(curlNoise(p, uint32_t(i % 7))));
    }
    qInfo("curl noise: largest |curl| sampled %.3f, proven bound %.3f (%.1fx)", curlMax, kCurlNoiseBound,
          kCurlNoiseBound / curlMax);
    QVERIFY(curlMax > 0.5 && curlMax <= kCurlNoiseBound);

    const HeightFieldCollider ground = hills(dvec3(0, 0, -3));
    struct Case {
      const char* what;
      EmitterDesc e;
      bool collide;
    };
    std::vector<Case> cases;
    EmitterDesc f = fountain();
    cases.push_back({"fountain (disc, drag, wind)", f, false});
    EmitterDesc box = f;
    box.shape = Shape::Box, box.boxHalf = {3, 1, 2}, box.drag = 0.0, box.speedMax = 9.0;
    cases.push_back({"box, no drag", box, false});
    EmitterDesc stiff = f;
    stiff.shape = Shape::Sphere, stiff.drag = 1e4, stiff.wind = {20, 0, 0};
    cases.push_back({"sphere, k = 1e4", stiff, false});
    EmitterDesc turb = f;
    turb.turbulence = 4.0, turb.turbulenceFrequency = 0.7, turb.drag = 0.2;
    cases.push_back({"turbulence", turb, false});
    EmitterDesc keyed = f;
    keyed.windKeys = {{0.0, {0, 0, 0}}, {1.0, {15, -4, 0}}, {3.0, {-10, 2, 1}}};
    keyed.drag = 2.0;
    cases.push_back({"keyed wind", keyed, false});
    EmitterDesc bounce = f;
    bounce.collision = CollisionMode::Bounce, bounce.restitution = 1.0, bounce.friction = 0.0, bounce.speedMax = 12;
    bounce.wind = {8, 3, 0};
    cases.push_back({"perfect bounce in wind", bounce, true});
    EmitterDesc cone = f;
    cone.shape = Shape::Cone, cone.radius = 2.0, cone.gravity = dvec3(0.0), cone.drag = 0.0;
    cases.push_back({"cone, no forces", cone, false});
    for (const Case& c : cases) {
      const std::optional<ParticleBound> b = particleBound(c.e);
      QVERIFY2(b, c.what);
      std::string err;
      EvaluatorInputs in;
      if (c.collide) in.colliders = {&ground};
      auto ev = Evaluator::create(c.e, in, err);
      QVERIFY2(ev, err.c_str());
      double worst = 0.0, fastest = 0.0;  // largest shares of the radius and of the speed bound reached
      size_t n = 0;
      const double vmax = speedBound(c.e, c.e.lifetimeMax);
      for (double t : {0.1, 0.7, 1.9, 3.3, 5.0}) {
        for (const Particle& p : ev->frame(t).particles) {
          worst = std::max(worst, glm::length(p.position - b->centre) / b->radius);
          fastest = std::max(fastest, glm::length(p.velocity) / vmax);
          QVERIFY(glm::length(p.velocity) <= speedBound(c.e, p.age) * (1.0 + 1e-12));
          ++n;
        }
      }
      QVERIFY2(fastest <= 1.0, c.what);
      qInfo("%-28s radius %9.2f m; %zu particles, farthest at %.3f of it", c.what, b->radius, n, worst);
      QVERIFY(n > 100);
      QVERIFY2(worst <= 1.0, c.what);
    }
    // Terrain shape: needs the ground's height range; then it holds too.
    EmitterDesc terr = f;
    terr.shape = Shape::Terrain;
    terr.boxHalf = {6, 4, 1.5};
    QVERIFY(!particleBound(terr));
    std::string err;
    EvaluatorInputs tin;
    tin.ground = &ground;
    auto tev = Evaluator::create(terr, tin, err);
    QVERIFY2(tev, err.c_str());
    double zmin = 1e30, zmax = -1e30;
    for (double x = -6; x <= 6; x += 0.05)
      for (double y = -4; y <= 4; y += 0.05) {
        zmin = std::min(zmin, ground.height(terr.origin.x + x, terr.origin.y + y));
        zmax = std::max(zmax, ground.height(terr.origin.x + x, terr.origin.y + y));
      }
    BoundInputs groundIn;
    groundIn.groundRange = std::make_pair(zmin - 0.01, zmax + 0.01);
    const auto tb = particleBound(terr, groundIn);
    QVERIFY(tb);
    for (const Particle& p : tev->frame(2.0).particles) QVERIFY(glm::length(p.position - tb->centre) <= tb->radius);
    // A mesh shape: bounded by its surface's box (a pitched roof, off the origin).
    EmitterDesc mesh = f;
    mesh.shape = Shape::Mesh, mesh.mesh = "Roof";
    QVERIFY(!particleBound(mesh));
    const TriangleSurface roof({dvec3(4, -3, 6), dvec3(10, -3, 6), dvec3(7, -3, 9), dvec3(4, 5, 6), dvec3(10, 5, 6),
                                dvec3(7, 5, 9), dvec3(4, -3, 6), dvec3(7, -3, 9), dvec3(7, 5, 9)});
    EvaluatorInputs min;
    min.surface = &roof;
    auto mev = Evaluator::create(mesh, min, err);
    QVERIFY2(mev, err.c_str());
    BoundInputs roofIn;
    roofIn.surface = &roof;
    const auto mb = particleBound(mesh, roofIn);
    QVERIFY(mb && glm::length(mb->centre - dvec3(7, 1, 7.5)) < 1e-12);
    size_t meshParticles = 0;
    for (double t : {0.5, 2.0, 4.0})
      for (const Particle& p : mev->frame(t).particles) {
        QVERIFY(glm::length(p.position - mb->centre) <= mb->radius);
        ++meshParticles;
      }
    QVERIFY(meshParticles > 100);
    // No bound: a moving world-space emitter without where it was at the births.
    EmitterDesc world = f;
    world.space = Space::World;
    BoundInputs moving;
    moving.moves = true;
    QVERIFY(!particleBound(world, moving) && particleBound(world) && particleBound(f, moving));
  }

  void replayConvergesToTheExactSolutionWithoutForcesThatNeedIt() {
    // Collision on but never touching (ground far below): the replay is the
    // exact motion step by step, so it matches the closed form to rounding.
    EmitterDesc e = fountain();
    e.collision = CollisionMode::Bounce;
    const HeightFieldCollider deep([](double, double) { return -1e4; });
    std::string err;
    auto ev = Evaluator::create(e, {nullptr, {&deep}}, err);
    auto ex = Evaluator::create(fountain(), {}, err);
    QVERIFY(ev && ex);
    const Frame a = ev->frame(5.0), b = ex->frame(5.0);
    QCOMPARE(a.particles.size(), b.particles.size());
    double worst = 0;
    for (size_t i = 0; i < a.particles.size(); ++i)
      worst = std::max(worst, maxAbs(a.particles[i].position - b.particles[i].position));
    qInfo("replay without contacts vs closed form: %.3g m", worst);
    QVERIFY(worst < 1e-9);
  }

  void collisionNeverPenetratesMoreThanAMillimetre() {
    for (CollisionMode mode : {CollisionMode::Bounce, CollisionMode::Stick, CollisionMode::Kill}) {
      EmitterDesc e = fountain();
      e.collision = mode;
      e.restitution = 0.7;
      e.turbulence = 3.0;
      e.speedMin = 5, e.speedMax = 15;
      e.replayStep = 1.0 / 30.0;  // coarse on purpose
      const HeightFieldCollider ground = hills();
      std::string err;
      auto ev = Evaluator::create(e, {nullptr, {&ground}}, err);
      QVERIFY(ev);
      double worst = -1e9;
      size_t checked = 0, killed = 0;
      for (double t = 1.0; t < 9.0; t += 0.37) {
        const Frame f = ev->frame(t);
        killed += f.killed;
        for (const Particle& p : f.particles) {
          const dvec3 w = e.origin + p.position;
          worst = std::max(worst, ground.height(w.x, w.y) - w.z);
          ++checked;
        }
      }
      qInfo("%s: %zu particle states, deepest %.3g m below the ground (negative: above), %zu killed", collisionName(mode),
            checked, worst, killed);
      QVERIFY(checked > 1000);
      QVERIFY2(worst <= 1e-3, collisionName(mode));
      if (mode == CollisionMode::Kill) QVERIFY(killed > 0);
    }
    // A triangle-mesh floor (two triangles at z = 0.5 world).
    EmitterDesc e = fountain();
    e.collision = CollisionMode::Bounce;
    e.restitution = 0.9;
    const TriangleMeshCollider floor({{-50, -50, 0.5}, {50, -50, 0.5}, {50, 50, 0.5}, {-50, -50, 0.5}, {50, 50, 0.5},
                                      {-50, 50, 0.5}});
    std::string err;
    auto ev = Evaluator::create(e, {nullptr, {&floor}}, err);
    double worst = -1e9;
    for (double t = 1.0; t < 8.0; t += 0.5)
      for (const Particle& p : ev->frame(t).particles) worst = std::max(worst, 0.5 - (e.origin.z + p.position.z));
    qInfo("mesh floor: deepest %.3g m", worst);
    QVERIFY(worst <= 1e-3);
  }

  void restitutionOneConservesEnergyAndZeroRests() {
    EmitterDesc e;
    e.name = "Ball";
    e.rate = 0.0;
    e.bursts = {{0.0, 1}};
    e.lifetimeMin = e.lifetimeMax = 100.0;
    e.speedMin = e.speedMax = 1.0;
    e.direction = {1, 0, 0};
    e.origin = {0, 0, 2.0};
    e.collision = CollisionMode::Bounce;
    e.restitution = 1.0;
    e.friction = 0.0;
    e.restSpeed = 0.0;
    const HeightFieldCollider flat([](double, double) { return 0.0; }, [](double, double) { return dvec3(0, 0, 1); });
    std::string err;
    auto ev = Evaluator::create(e, {nullptr, {&flat}}, err);
    QVERIFY2(ev, err.c_str());
    const double g = 9.81, e0 = 0.5 * 1.0 + g * 2.0;
    double worst = 0, lowest = 1e9;
    for (double t = 0.05; t < 30.0; t += 0.0917) {
      const Particle p = ev->particle({1, 0}, t);
      QVERIFY(p.alive);
      const double en = 0.5 * glm::dot(p.velocity, p.velocity) + g * (e.origin.z + p.position.z);
      worst = std::max(worst, std::abs(en - e0) / e0);
      lowest = std::min(lowest, e.origin.z + p.position.z);
    }
    qInfo("restitution 1: energy error %.3g (relative) over 30 s, lowest z %.3g m", worst, lowest);
    QVERIFY(worst < 1e-3);
    QVERIFY(lowest > -1e-3 && lowest < 0.1);  // it did reach the ground

    e.restitution = 0.0;
    e.restSpeed = 0.05;
    ev = Evaluator::create(e, {nullptr, {&flat}}, err);
    const double impact = std::sqrt(2.0 * 2.0 / g);
    for (double t = impact + 0.05; t < 10.0; t += 0.5) {
      const Particle p = ev->particle({1, 0}, t);
      QCOMPARE(int(p.fate), int(Fate::Resting));
      QCOMPARE(p.velocity, dvec3(0.0));
      const double z = e.origin.z + p.position.z;
      QVERIFY(z >= 0.0 && z < 1e-3);
      QVERIFY(std::abs(p.position.x - impact) < 0.02);  // where it landed (speed 1 m/s along x)
    }
  }

  void stiffEmittersStayFiniteThroughTheEvaluator() {
    // k = 1e7 with turbulence (replayed) and without: every state finite, at
    // the terminal velocity w + (g + a_turb) / k after the first microseconds.
    for (double turbulence : {0.0, 50.0}) {
      EmitterDesc e = fountain();
      e.drag = 1e7;
      e.turbulence = turbulence;
      e.replayStep = 1.0 / 60.0;  // k h = 1.7e5
      std::string err;
      auto ev = Evaluator::create(e, {}, err);
      QVERIFY2(ev, err.c_str());
      const Frame f = ev->frame(3.0);
      QVERIFY(f.particles.size() > 500);
      double worst = 0;
      for (const Particle& p : f.particles) {
        QVERIFY(finite(p.position) && finite(p.velocity));
        if (p.age > 1e-3) worst = std::max(worst, maxAbs(p.velocity - e.wind) - (9.81 + 3 * turbulence) / e.drag);
      }
      qInfo("k = 1e7, turbulence %g: largest speed beyond the terminal bound %.3g m/s", turbulence, worst);
      QVERIFY(worst <= 1e-9);
    }
  }

  void utmCoordinatesLoseNothing() {
    EmitterDesc near = fountain();
    EmitterDesc far = near;
    far.origin = {500000.0, 4400000.0, 300.0};
    std::string err;
    auto a = Evaluator::create(near, {}, err), b = Evaluator::create(far, {}, err);
    const Frame fa = a->frame(6.0), fb = b->frame(6.0);
    QCOMPARE(fa.particles.size(), fb.particles.size());
    for (size_t i = 0; i < fa.particles.size(); ++i) QCOMPARE(fa.particles[i].position, fb.particles[i].position);
    // With a terrain at UTM coordinates: the same hills around each origin (ground 2 m below).
    near.collision = far.collision = CollisionMode::Bounce;
    const HeightFieldCollider ga = hills({0, 0, 0}), gb = hills({500000.0, 4400000.0, 298.0});
    a = Evaluator::create(near, {nullptr, {&ga}}, err);
    b = Evaluator::create(far, {nullptr, {&gb}}, err);
    double worst = 0, deepest = -1e9;
    for (double t : {2.0, 4.0, 6.0}) {
      const Frame ca = a->frame(t), cb = b->frame(t);
      QCOMPARE(ca.particles.size(), cb.particles.size());
      for (size_t i = 0; i < ca.particles.size(); ++i) {
        worst = std::max(worst, maxAbs(ca.particles[i].position - cb.particles[i].position));
        const dvec3 w = far.origin + cb.particles[i].position;
        deepest = std::max(deepest, gb.height(w.x, w.y) - w.z);
        // What a renderer receives: float, relative to the origin.
        const glm::vec3 rel(cb.particles[i].position);
        QVERIFY(maxAbs(dvec3(rel) - cb.particles[i].position) < 1e-5);
      }
    }
    qInfo("UTM (500000, 4400000, 300) vs origin: %.3g m apart, deepest %.3g m", worst, deepest);
    // Packed for the GPU relative to a camera 40 m away at UTM coordinates: float positions to 1e-5 m.
    const dvec3 camera = far.origin + dvec3(30.0, -25.0, 8.0);
    const Frame cf = b->frame(4.0);
    const std::vector<PackedParticle> packed = packFrame(cf, far.origin, camera, far.seed);
    QCOMPARE(packed.size(), cf.particles.size());
    double packErr = 0;
    for (size_t i = 0; i < packed.size(); ++i) {
      const dvec3 truth = (far.origin + cf.particles[i].position) - camera;  // both near, exact enough in double
      const dvec3 got(packed[i].position[0], packed[i].position[1], packed[i].position[2]);
      packErr = std::max(packErr, maxAbs(got - truth));
    }
    qInfo("packed (float, camera-relative) positions: %.3g m from the double ones", packErr);
    QVERIFY(packErr < 1e-5);
    QVERIFY(worst < 1e-4);
    QVERIFY(deepest <= 1e-3);
  }

  void capKeepsTheOldestAndCountsTheRest() {
    EmitterDesc e;
    e.name = "Blizzard";
    e.rate = 1e7;
    e.lifetimeMin = 0.5;
    e.lifetimeMax = 1.0;
    e.maxLive = 100000;
    std::string err;
    auto ev = Evaluator::create(e, {}, err);
    QVERIFY2(ev, err.c_str());
    const Frame f = ev->frame(3.0);
    qInfo("%s", f.message.c_str());
    QCOMPARE(f.particles.size(), size_t(100000));
    QVERIFY(f.leftOutExact);
    QVERIFY(f.live > 7000000 && f.live < 8000000);  // 1e7/s x 0.75 s expected
    QCOMPARE(f.leftOut, f.live - 100000);
    QCOMPARE(ev->liveCount(3.0), f.live);
    QVERIFY(f.message.find("Blizzard") != std::string::npos);
    QVERIFY(f.message.find(std::to_string(f.leftOut)) != std::string::npos);
    for (size_t i = 1; i < f.particles.size(); ++i) QVERIFY(f.particles[i].birth >= f.particles[i - 1].birth);
    // Too many to count one by one (7.5e7 live): estimated from a sample, said so.
    e.lifetimeMin = 5.0;
    e.lifetimeMax = 10.0;
    e.bursts = {{2.5, 3000000}};
    ev = Evaluator::create(e, {}, err);
    const Frame big = ev->frame(20.0);
    qInfo("%s", big.message.c_str());
    QVERIFY(!big.leftOutExact);
    QVERIFY(big.message.find("(estimated)") != std::string::npos);
    QCOMPARE(big.particles.size(), size_t(100000));
    const double expected = 1e7 * 7.5;  // the burst is dead by t = 20
    QVERIFY2(std::abs(double(big.live) - expected) < 0.01 * expected, qPrintable(QString::number(big.live)));
    const Frame withBurst = ev->frame(9.0);  // the burst (age 6.5 s, 70% alive) is in the window
    const double expected2 = 1e7 * (5.0 + (9.0 - 5.0) - 0.5 * (9.0 - 5.0) * (9.0 - 5.0) / 5.0) + 0.7 * 3e6;
    qInfo("%s", withBurst.message.c_str());
    QVERIFY2(std::abs(double(withBurst.live) - expected2) < 0.01 * expected2,
             qPrintable(QString("%1 vs %2").arg(withBurst.live).arg(expected2)));
    e.bursts.clear();
    // Lifetime 0: nothing is ever alive; gravity 0: straight lines.
    e.lifetimeMin = e.lifetimeMax = 0.0;
    e.rate = 1000;
    ev = Evaluator::create(e, {}, err);
    QVERIFY(ev->frame(2.0).particles.empty());
    e.lifetimeMin = e.lifetimeMax = 3.0;
    e.gravity = dvec3(0.0);
    ev = Evaluator::create(e, {}, err);
    for (const Particle& p : ev->frame(2.0).particles)
      QVERIFY(maxAbs(p.position - ev->start(p.id).state.v * p.age) < 1e-12);
  }

  void noiseGradientAndCurlAreRight() {
    double worstGrad = 0, worstDiv = 0;
    for (int i = 0; i < 200; ++i) {
      const dvec3 p{unitFromHash(hashU32(i)) * 40 - 20, unitFromHash(hashU32(i + 1000)) * 40 - 20,
                    unitFromHash(hashU32(i + 2000)) * 40 - 20};
      const NoiseSample s = gradientNoise(p, 5);
      const double h = 1e-5;
      for (int a = 0; a < 3; ++a) {
        dvec3 d(0.0);
        d[a] = h;
        const double fd = (gradientNoise(p + d, 5).value - gradientNoise(p - d, 5).value) / (2 * h);
        worstGrad = std::max(worstGrad, std::abs(fd - s.gradient[a]));
      }
      double div = 0;
      for (int a = 0; a < 3; ++a) {
        dvec3 d(0.0);
        d[a] = h;
        div += (curlNoise(p + d, 5)[a] - curlNoise(p - d, 5)[a]) / (2 * h);
      }
      worstDiv = std::max(worstDiv, std::abs(div));
    }
    qInfo("noise gradient vs finite differences %.3g; curl divergence %.3g", worstGrad, worstDiv);
    QVERIFY(worstGrad < 1e-6);
    QVERIFY(worstDiv < 1e-5);
    // Far along in time (t * evolution past 2^31 lattice cells): finite, and still a varying field.
    const dvec3 a = turbulenceAt({1, 2, 3}, 1.1e7, 1.0, 1.0, 1e3, 9), b = turbulenceAt({1.5, 2, 3}, 1.1e7, 1.0, 1.0, 1e3, 9);
    QVERIFY(finite(a) && finite(b) && maxAbs(a - b) > 0.0);
  }

  void presetsAreValidAndRun() {
    const HeightFieldCollider ground = hills({500000.0, 4400000.0, 300.0});
    for (const std::string& name : presetNames()) {
      PresetOptions o;
      o.at = {500000.0, 4400000.0, 300.0};
      o.area = glm::dvec4(499980.0, 4399980.0, 500020.0, 4400020.0);
      o.seed = 3;
      std::string err;
      const std::vector<EmitterDesc> es = makePreset(name, o, err);
      QVERIFY2(!es.empty(), err.c_str());
      for (const EmitterDesc& e : es) {
        const std::vector<std::string> v = validate(e);
        QVERIFY2(v.empty(), v.empty() ? "" : v.front().c_str());
        std::string jerr;
        const auto back = emitterFromJsonText(hs::writeJson(emitterToJson(e)), jerr);
        QVERIFY2(back && *back == e, jerr.c_str());
        auto ev = Evaluator::create(e, {nullptr, {&ground}}, err);
        QVERIFY2(ev, err.c_str());
        const Frame f = ev->frame(12.0);
        qInfo("%s: %zu live at t = 12 s, %llu replay steps", e.name.c_str(), f.particles.size(),
              (unsigned long long)f.replaySteps);
        QVERIFY2(!f.particles.empty(), e.name.c_str());
        QVERIFY(f.leftOut == 0);
        for (const Particle& p : f.particles) QVERIFY(finite(p.position) && finite(p.velocity) && std::isfinite(p.size));
      }
    }
    std::string err;
    QVERIFY(makePreset("rain", {}, err).empty());
    QVERIFY(err.find("snow, fog, torch, campfire, dust") != std::string::npos);
    PresetOptions o;
    o.rate = 123.0;
    o.name = "Monastery torch";
    const auto torch = torchPreset(o);
    QCOMPARE(torch.size(), size_t(2));
    QCOMPARE(torch[0].rate, 123.0);
    QCOMPARE(torch[0].name, std::string("Monastery torch flame"));
  }

  void spritesAreDeterministicAndShaped() {
    const hs::Image a = snowflakeSprite(64, 1), b = snowflakeSprite(64, 1), c = snowflakeSprite(64, 2);
    QVERIFY(a == b);
    QVERIFY(!(a == c));
    auto alpha = [](const hs::Image& im, int x, int y) { return int(im.rgba8[(size_t(y) * size_t(im.width) + size_t(x)) * 4 + 3]); };
    QCOMPARE(alpha(a, 0, 0), 0);
    QVERIFY(alpha(a, 32, 32) > 200);  // the hub
    // Six-fold: coverage sampled along a circle repeats every 60 degrees.
    int agree = 0, total = 0;
    for (int i = 0; i < 360; ++i) {
      const double ang = i * std::numbers::pi / 180.0, ang2 = ang + std::numbers::pi / 3.0;
      const double r = 20.0;
      const int v1 = alpha(a, int(32 + r * std::cos(ang)), int(32 + r * std::sin(ang))) > 127;
      const int v2 = alpha(a, int(32 + r * std::cos(ang2)), int(32 + r * std::sin(ang2))) > 127;
      agree += v1 == v2;
      ++total;
    }
    QVERIFY2(agree > total * 9 / 10, qPrintable(QString("%1 of %2").arg(agree).arg(total)));
    const hs::Image s = smokePuffSprite(64, 4);
    QVERIFY(s == smokePuffSprite(64, 4));
    QCOMPARE(alpha(s, 0, 0), 0);
    QVERIFY(alpha(s, 32, 32) > 100);
    const Flipbook f = flameFlipbook(32, 16, 9), g = flameFlipbook(32, 16, 9);
    QVERIFY(f.atlas == g.atlas);
    QCOMPARE(f.columns, 4);
    QCOMPARE(f.rows, 4);
    QCOMPARE(f.atlas.width, 128);
    // Frames differ from each other, and the flame is brighter at its base than at its tip.
    int differing = 0, baseA = 0, tipA = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        differing += alpha(f.atlas, x, y) != alpha(f.atlas, 32 + x, y);
        (y > 20 ? baseA : tipA) += y > 20 || y < 11 ? alpha(f.atlas, x, y) : 0;
      }
    QVERIFY(differing > 20);
    QVERIFY(baseA > tipA);
  }

  void badInputNamesEmitterAndField() {
    EmitterDesc e = fountain();
    e.name = "Torch";
    auto expect = [&](const EmitterDesc& x, const char* field) {
      const std::vector<std::string> v = validate(x);
      QVERIFY2(!v.empty(), field);
      qInfo("%s", v.front().c_str());
      QVERIFY2(v.front().find("emitter 'Torch'") != std::string::npos, v.front().c_str());
      QVERIFY2(v.front().find(field) != std::string::npos, v.front().c_str());
      std::string err;
      QVERIFY(!Evaluator::create(x, {}, err));
      QCOMPARE(err, v.front());
    };
    QVERIFY(validate(e).empty());
    EmitterDesc x = e;
    x.rate = -5;
    expect(x, "rate_per_s");
    x = e, x.rate = NAN;
    expect(x, "rate_per_s");
    x = e, x.drag = NAN;
    expect(x, "drag_per_s");
    x = e, x.drag = -1;
    expect(x, "drag_per_s");
    x = e, x.lifetimeMin = -1;
    expect(x, "lifetime_s");
    x = e, x.lifetimeMin = 5, x.lifetimeMax = 1;
    expect(x, "lifetime_s");
    x = e, x.sizeMax = NAN;
    expect(x, "size_m");
    x = e, x.direction = dvec3(0.0);
    expect(x, "direction");
    x = e, x.rateKeys.keys = {{0, 10}, {1, 20}, {1, 30}};
    expect(x, "rate_keys[2]");
    QVERIFY(validate(x).front().find("coincides") != std::string::npos);
    x = e, x.rateKeys.keys = {{0, 10}, {1, -20}};
    expect(x, "rate_keys[1]");
    x = e, x.sizeOverLife.keys = {{0, 1}, {1.5, 2}};
    expect(x, "size_over_life[1]");
    x = e, x.bursts = {{1.0, -3}};
    expect(x, "bursts[0]");
    x = e, x.shape = Shape::Mesh;
    expect(x, "mesh");
    // A named mesh that is not there.
    x.mesh = "Monastery roof";
    std::string err;
    QVERIFY(!Evaluator::create(x, {}, err));
    QVERIFY(err.find("'Monastery roof' is missing") != std::string::npos && err.find("Torch") != std::string::npos);
    // A replay that would take too many steps.
    x = e, x.turbulence = 1, x.lifetimeMin = x.lifetimeMax = 5000, x.replayStep = 1e-4;
    QVERIFY(!Evaluator::create(x, {}, err));
    QVERIFY(err.find("replay_step_s") != std::string::npos);
  }

  void jsonIsStrict() {
    const EmitterDesc e = fountain();
    const hs::Json good = emitterToJson(e);
    std::string err;
    auto round = emitterFromJsonText(hs::writeJson(good), err);
    QVERIFY2(round, err.c_str());
    QVERIFY(*round == e);
    auto bad = [&](hs::Json j, const char* want) {
      std::string why;
      QVERIFY(!emitterFromJson(j, why));
      qInfo("%s", why.c_str());
      QVERIFY2(why.find(want) != std::string::npos, why.c_str());
      QVERIFY2(why.find("Fountain") != std::string::npos, why.c_str());
    };
    hs::Json j = good;
    j["drag_per_s"] = NAN;
    bad(j, "drag_per_s");
    j = good, j["drag_per_s"] = "strong";
    bad(j, "drag_per_s");
    j = good, j.erase("lifetime_s");
    bad(j, "lifetime_s: missing");
    j = good, j["lifetime_s"] = hs::Json::array({1.0});
    bad(j, "lifetime_s");
    j = good, j["shape"] = "torus";
    bad(j, "'torus' is not one of");
    j = good, j["dragg_per_s"] = 1.0;
    bad(j, "unknown field");
    j = good, j["rate_keys"] = hs::Json::array({hs::Json::array({0.0, 1.0}), hs::Json::array({0.0, 2.0})});
    bad(j, "coincides");
    j = good, j["colour_over_life"] = hs::Json::array({hs::Json::array({0.0, 1.0, 1.0})});
    bad(j, "colour_over_life[0]");
    j = good, j["bursts"] = hs::Json::array({hs::Json::array({0.0, 2.5})});
    bad(j, "bursts");
    // Text: syntax errors with line and column; NaN is not JSON.
    QVERIFY(!emitterFromJsonText("{\"name\": \"Fountain\",\n \"drag_per_s\": NaN}", err));
    QVERIFY2(err.find("line 2") != std::string::npos, err.c_str());
    // setEmitterField: the declaration's checks and messages.
    EmitterDesc s = e;
    QVERIFY(setEmitterField(s, "drag_per_s", 3.0, err) && s.drag == 3.0);
    QVERIFY(!setEmitterField(s, "drag_per_s", -3.0, err));
    QVERIFY2(err.find("emitter 'Fountain', field 'drag_per_s'") != std::string::npos, err.c_str());
    QVERIFY(!setEmitterField(s, "speed_m_per_s", hs::Json::array({5.0, 1.0}), err));
    QVERIFY(!setEmitterField(s, "no_such", 1.0, err));
    // Every declared key appears in the file once.
    for (const hs::ParamDecl& d : emitterParamDecls()) QVERIFY2(good.contains(d.key), d.key.c_str());
    QCOMPARE(emitterFields().size(), emitterParamDecls().size());
  }

  // Keys a later format added are optional in an older file's emitter (with
  // their defaults) and required in the current one.
  void olderFormatsTakeDefaultsForLaterKeys() {
    EmitterDesc e = fountain();
    e.space = Space::World;
    e.drawMesh = "Pebble";
    hs::Json j = emitterToJson(e);
    QCOMPARE(j["space"].get<std::string>(), std::string("world"));
    QCOMPARE(j["draw_mesh"].get<std::string>(), std::string("Pebble"));
    j.erase("space");
    j.erase("draw_mesh");
    std::string err;
    const auto old = emitterFromJson(j, err, 10);
    QVERIFY2(old, err.c_str());
    QCOMPARE(int(old->space), int(Space::Local));
    QVERIFY(old->drawMesh.empty());
    QVERIFY(emitterKeyAddedAfter("space", 10) && !emitterKeyAddedAfter("space", 11));
    QVERIFY(!emitterKeyAddedAfter("lifetime_s", 10));
    // A format-10 emitter still needs every key format 10 had.
    hs::Json j10 = j;
    j10.erase("lit");
    QVERIFY(!emitterFromJson(j10, err, 10));
    QVERIFY2(err.find("lit: missing") != std::string::npos, err.c_str());
    // The current format requires them.
    QVERIFY(!emitterFromJson(j, err));
    QVERIFY2(err.find("space: missing") != std::string::npos, err.c_str());
    // And a value of theirs is checked like any other's.
    j["space"] = "orbit";
    j["draw_mesh"] = "";
    QVERIFY(!emitterFromJson(j, err));
    QVERIFY2(err.find("'orbit' is not one of") != std::string::npos, err.c_str());
  }
};

QTEST_GUILESS_MAIN(TestParticles)
#include "test_particles.moc"
