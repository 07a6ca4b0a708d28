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
