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
// The explicit integrators below are references for tests and the
// benchmark's error-against-run-time table, not used by the evaluator.
#include <functional>

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

// The exact state after tau >= 0.
Kinematics exactMotion(const Kinematics& s, const Forces& f, double tau);

// One step of size h of the reference integrators (acceleration from `f`).
Kinematics eulerStep(const Kinematics& s, const Forces& f, double h);              // explicit Euler
Kinematics semiImplicitEulerStep(const Kinematics& s, const Forces& f, double h);  // v first, then x with the new v
Kinematics rk4Step(const Kinematics& s, const Forces& f, double h);                // classical Runge-Kutta

// Integrates to time T with steps of h (the last step shortened to land on T).
enum class Integrator { Euler, SemiImplicitEuler, Rk4, Exact };
const char* integratorName(Integrator i);
Kinematics integrate(Integrator which, const Kinematics& s, const Forces& f, double T, double h);

}  // namespace hs::particles
