#pragma once
// The motion of one particle between events (docs/particles.md,
// "Equations"):
//     dx/dt = v,   dv/dt = g + k (w - v)
// with constant gravity g, drag k >= 0 and wind (air velocity) w. Its exact
// solution after time tau, written so that neither k -> 0 nor k tau -> inf
// loses accuracy or divides 0 by 0:
//     a0   = g + k (w - v0)                  (the acceleration at the start)
//     v(t) = v0 + a0 tau phi1(k tau)
//     x(t) = x0 + v0 tau + a0 tau^2 phi2(k tau)
//     phi1(z) = (1 - e^-z) / z = -expm1(-z) / z            phi1(0) = 1
//     phi2(z) = (z - 1 + e^-z) / z^2 = (z + expm1(-z)) / z^2   phi2(0) = 1/2
// phi2 uses its Taylor series below z = 0.25 (the closed form cancels
// there), so both are accurate to a few ulps for every z >= 0; for
// k tau >> 1, v -> w + g/k and x grows by (w + g/k) tau, as it must.
//
// Wind keyed over time (piecewise linear, held outside its keys) keeps an
// exact solution: on a stretch where the forcing f(s) = g + k w(s) is
// f0 + f1 s,
//     v(tau) = v0 + tau phi1(k tau) (f0 - k v0) + tau^2 phi2(k tau) f1
//     x(tau) = x0 + v0 tau + tau^2 phi2(k tau) (f0 - k v0) + tau^3 phi3(k tau) f1
//     phi3(z) = (z^2/2 - z + 1 - e^-z) / z^3                  phi3(0) = 1/6
// applied stretch by stretch between wind keys.
//
// The explicit integrators below are references for tests and the
// benchmark's error-against-run-time table, not used by the evaluator.
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace hs::particles {

struct Forces {
  glm::dvec3 gravity{0.0};
  double drag = 0.0;
  glm::dvec3 wind{0.0};
};

struct Kinematics {
  glm::dvec3 x{0.0};
  glm::dvec3 v{0.0};
};

double phi1(double z);
double phi2(double z);
double phi3(double z);

// A wind key: the air's velocity at scene time t.
struct WindKey {
  double t = 0.0;
  glm::dvec3 wind{0.0};
  bool operator==(const WindKey&) const = default;
};
// The wind at scene time t (keys strictly increasing in t; none: `fallback`).
glm::dvec3 windAt(const std::vector<WindKey>& keys, double t, const glm::dvec3& fallback);

// The exact state after tau >= 0.
Kinematics exactMotion(const Kinematics& s, const Forces& f, double tau);

// The exact state after tau >= 0 with forcing f0 + f1 s (s: time since the start).
Kinematics exactMotionLinear(const Kinematics& s, double drag, const glm::dvec3& f0, const glm::dvec3& f1, double tau);
// The exact state after tau >= 0 starting at scene time t0 under keyed wind
// (f.wind is used when `keys` is empty: then this is exactMotion).
Kinematics exactMotionKeyed(const Kinematics& s, const Forces& f, const std::vector<WindKey>& keys, double t0,
                            double tau);

// One step of size h of the reference integrators (acceleration from `f`).
Kinematics eulerStep(const Kinematics& s, const Forces& f, double h);              // explicit Euler
Kinematics semiImplicitEulerStep(const Kinematics& s, const Forces& f, double h);  // v first, then x with the new v
Kinematics rk4Step(const Kinematics& s, const Forces& f, double h);                // classical Runge-Kutta

// Integrates to time T with steps of h (the last step shortened to land on T).
enum class Integrator { Euler, SemiImplicitEuler, Rk4, Exact };
const char* integratorName(Integrator i);
Kinematics integrate(Integrator which, const Kinematics& s, const Forces& f, double T, double h);

}  // namespace hs::particles
