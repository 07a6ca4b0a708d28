#include "sequencer/interpolation.h"

#include <algorithm>
#include <cmath>

namespace hs::sequencer {

double easeValue(Ease ease, double u) {
  switch (ease) {
    case Ease::None: return u;
    case Ease::In: return u * u * (2.0 - u);
    case Ease::Out: {
      const double v = 1.0 - u;
      return 1.0 - v * v * (2.0 - v);
    }
    case Ease::InOut: return u * u * (3.0 - 2.0 * u);
  }
  return u;
}

double easeSlope(Ease ease, double u) {
  switch (ease) {
    case Ease::None: return 1.0;
    case Ease::In: return u * (4.0 - 3.0 * u);
    case Ease::Out: {
      const double v = 1.0 - u;
      return v * (4.0 - 3.0 * v);
    }
    case Ease::InOut: return 6.0 * u * (1.0 - u);
  }
  return 1.0;
}

double hermite(double p0, double d0, double p1, double d1, double u) {
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
  const double h10 = u3 - 2.0 * u2 + u;
  const double h01 = -2.0 * u3 + 3.0 * u2;
  const double h11 = u3 - u2;
  return h00 * p0 + h10 * d0 + h01 * p1 + h11 * d1;
}

double hermiteSlope(double p0, double d0, double p1, double d1, double u) {
  const double u2 = u * u;
  return (6.0 * u2 - 6.0 * u) * p0 + (3.0 * u2 - 4.0 * u + 1.0) * d0 + (-6.0 * u2 + 6.0 * u) * p1 +
         (3.0 * u2 - 2.0 * u) * d1;
}

double clampedSlope(double dPrev, double dNext, double hPrev, double hNext) {
  if (!(dPrev * dNext > 0.0)) return 0.0;  // extreme, plateau (or NaN): flat
  const double w1 = 2.0 * hNext + hPrev;
  const double w2 = hNext + 2.0 * hPrev;
  return (w1 + w2) / (w1 / dPrev + w2 / dNext);
}

glm::dvec3 rotationVector(const glm::dquat& qIn) {
  glm::dquat q = qIn;
  if (q.w < 0.0) q = -q;  // angle in [0, pi]
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-300) return glm::dvec3(0.0);
  // atan2 keeps full precision near 0 and near pi, where acos(w) does not.
  const double angle = 2.0 * std::atan2(s, q.w);
  return v * (angle / s);
}

glm::dquat rotationFromVector(const glm::dvec3& v) {
  const double angle = glm::length(v);
  if (angle < 1e-300) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  const double half = 0.5 * angle;
  // sin(half)/angle written so that small angles keep their precision.
  const double k = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return glm::dquat(std::cos(half), v.x * k, v.y * k, v.z * k);
}

glm::dvec3 segmentRotation(const glm::dquat& earlier, const glm::dquat& later) {
  glm::dquat b = later;
  const double d = glm::dot(earlier, later);
  if (std::abs(d) <= kHalfTurnTolerance) {
    // Half a turn: choose the sign of `later` that makes the world-frame
    // rotation vector (b * conj(earlier)) point to +Z (else +Y, else +X).
    const glm::dquat w = later * glm::conjugate(earlier);
    const glm::dvec3 axis(w.x, w.y, w.z);
    constexpr double kAxisTol = 1e-9;
    double key = axis.z;
    if (std::abs(key) <= kAxisTol) key = axis.y;
    if (std::abs(key) <= kAxisTol) key = axis.x;
    if (key < 0.0) b = -b;
    glm::dquat r = glm::conjugate(earlier) * b;
    // rotationVector() folds w < 0 onto the other way; here w is ~0 and the
    // sign of the vector part must survive, so build the vector directly.
    const glm::dvec3 v(r.x, r.y, r.z);
    const double s = glm::length(v);
    if (s < 1e-300) return glm::dvec3(0.0);
    return v * (2.0 * std::atan2(s, r.w < 0.0 ? 0.0 : r.w) / s);
  }
  if (d < 0.0) b = -b;
  return rotationVector(glm::conjugate(earlier) * b);
}

glm::dquat slerpAlong(const glm::dquat& from, const glm::dvec3& bodyRotation, double u) {
  return from * rotationFromVector(bodyRotation * u);
}

glm::dquat slerpShortest(const glm::dquat& a, const glm::dquat& b, double u) {
  return slerpAlong(a, segmentRotation(a, b), u);
}

double rotationAngleBetween(const glm::dquat& a, const glm::dquat& b) {
  return glm::length(rotationVector(glm::conjugate(a) * b));
}

}  // namespace hs::sequencer
