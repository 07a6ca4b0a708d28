#include "particles/motion.h"

#include <cmath>

namespace hs::particles {

double phi1(double z) {
  if (z == 0.0) return 1.0;
  if (z < 1e-300) return 1.0;
  return -std::expm1(-z) / z;
}

double phi2(double z) {
  if (z < 0.25) {
    // sum_{n>=0} (-z)^n / (n + 2)!, to z^13 (relative error below 1e-17 at z = 0.25).
    static constexpr double c[] = {1.0 / 2,
                                   1.0 / 6,
                                   1.0 / 24,
                                   1.0 / 120,
                                   1.0 / 720,
                                   1.0 / 5040,
                                   1.0 / 40320,
                                   1.0 / 362880,
                                   1.0 / 3628800,
                                   1.0 / 39916800,
                                   1.0 / 479001600,
                                   1.0 / 6227020800.0,
                                   1.0 / 87178291200.0,
                                   1.0 / 1307674368000.0};
    double r = 0.0;
    for (int n = 13; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (z + std::expm1(-z)) / (z * z);
}

double phi3(double z) {
  if (z < 1.0) {
    // sum_{n>=0} (-z)^n / (n + 3)!, to z^17.
    double c[18];
    double f = 6.0;  // 3!
    for (int n = 0; n < 18; ++n) {
      c[n] = 1.0 / f;
      f *= double(n + 4);
    }
    double r = 0.0;
    for (int n = 17; n >= 0; --n) r = c[n] - z * r;
    return r;
  }
  return (0.5 * z * z - z - std::expm1(-z)) / (z * z * z);
}

glm::dvec3 windAt(const std::vector<WindKey>& keys, double t, const glm::dvec3& fallback) {
  if (keys.empty()) return fallback;
  if (t <= keys.front().t) return keys.front().wind;
  if (t >= keys.back().t) return keys.back().wind;
  size_t i = 1;
  while (keys[i].t < t) ++i;
  const WindKey &a = keys[i - 1], &b = keys[i];
  return a.wind + (b.wind - a.wind) * ((t - a.t) / (b.t - a.t));
}

Kinematics exactMotionLinear(const Kinematics& s, double drag, const glm::dvec3& f0, const glm::dvec3& f1, double tau) {
  const double z = drag * tau;
  const glm::dvec3 a0 = f0 - drag * s.v;
  const double p2 = phi2(z);
  Kinematics r;
  r.v = s.v + a0 * (tau * phi1(z)) + f1 * (tau * tau * p2);
  r.x = s.x + s.v * tau + a0 * (tau * tau * p2) + f1 * (tau * tau * tau * phi3(z));
  return r;
}

Kinematics exactMotionKeyed(const Kinematics& s0, const Forces& f, const std::vector<WindKey>& keys, double t0,
                            double tau) {
  if (keys.empty()) return exactMotion(s0, f, tau);
  Kinematics s = s0;
  const double end = t0 + tau;
  double t = t0;
  while (t < end) {
    // The stretch from t to the next key (or the end).
    size_t i = 0;
    while (i < keys.size() && keys[i].t <= t) ++i;
    const double next = i < keys.size() ? std::min(end, keys[i].t) : end;
    glm::dvec3 slope(0.0);
    if (i > 0 && i < keys.size()) slope = (keys[i].wind - keys[i - 1].wind) / (keys[i].t - keys[i - 1].t);
    const glm::dvec3 w = windAt(keys, t, f.wind);
    s = exactMotionLinear(s, f.drag, f.gravity + f.drag * w, f.drag * slope, next - t);
    t = next;
  }
  return s;
}

Kinematics exactMotion(const Kinematics& s, const Forces& f, double tau) {
  const double z = f.drag * tau;
  const glm::dvec3 a0 = f.gravity + f.drag * (f.wind - s.v);
  Kinematics r;
  r.v = s.v + a0 * (tau * phi1(z));
  r.x = s.x + s.v * tau + a0 * (tau * tau * phi2(z));
  return r;
}

namespace {
glm::dvec3 accel(const Forces& f, const glm::dvec3& v) { return f.gravity + f.drag * (f.wind - v); }
}  // namespace

Kinematics eulerStep(const Kinematics& s, const Forces& f, double h) {
  return {s.x + h * s.v, s.v + h * accel(f, s.v)};
}

Kinematics semiImplicitEulerStep(const Kinematics& s, const Forces& f, double h) {
  const glm::dvec3 v = s.v + h * accel(f, s.v);
  return {s.x + h * v, v};
}

Kinematics rk4Step(const Kinematics& s, const Forces& f, double h) {
  const glm::dvec3 k1x = s.v, k1v = accel(f, s.v);
  const glm::dvec3 v2 = s.v + 0.5 * h * k1v;
  const glm::dvec3 k2x = v2, k2v = accel(f, v2);
  const glm::dvec3 v3 = s.v + 0.5 * h * k2v;
  const glm::dvec3 k3x = v3, k3v = accel(f, v3);
  const glm::dvec3 v4 = s.v + h * k3v;
  const glm::dvec3 k4x = v4, k4v = accel(f, v4);
  return {s.x + (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x), s.v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)};
}

const char* integratorName(Integrator i) {
  switch (i) {
    case Integrator::Euler: return "euler";
    case Integrator::SemiImplicitEuler: return "semi-implicit euler";
    case Integrator::Rk4: return "rk4";
    case Integrator::Exact: return "exact";
  }
  return "?";
}

Kinematics integrate(Integrator which, const Kinematics& s0, const Forces& f, double T, double h) {
  Kinematics s = s0;
  double t = 0.0;
  while (t < T) {
    const double step = std::min(h, T - t);
    switch (which) {
      case Integrator::Euler: s = eulerStep(s, f, step); break;
      case Integrator::SemiImplicitEuler: s = semiImplicitEulerStep(s, f, step); break;
      case Integrator::Rk4: s = rk4Step(s, f, step); break;
      case Integrator::Exact: s = exactMotion(s, f, step); break;
    }
    // Steps counted, not summed, so T/h steps land on T without drift.
    t = (T - t <= h) ? T : t + h;
  }
  return s;
}

}  // namespace hs::particles
