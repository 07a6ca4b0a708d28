#include "sequencer/camera_path.h"

#include <algorithm>
#include <cmath>

namespace hs::sequencer {

namespace {

constexpr int kSubIntervals = 16;
// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGaussX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                               0.9061798459386640};
constexpr double kGaussW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                               0.2369268850561891};
constexpr double kGravity = 9.80665;

}  // namespace

PathSampler::PathSampler(const std::vector<glm::dvec3>& points) {
  if (points.empty()) return;
  origin_ = points.front();
  for (const glm::dvec3& p : points) {
    const glm::dvec3 rel = p - origin_;
    // Consecutive duplicates would make a zero-length span (a division by
    // zero in the spline); they add nothing to the shape.
    if (!points_.empty() && glm::length(rel - points_.back()) <= 1e-9 * (1.0 + glm::length(rel))) continue;
    points_.push_back(rel);
  }
  const size_t n = points_.size();
  knots_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i) knots_[i] = knots_[i - 1] + glm::length(points_[i] - points_[i - 1]);
  second_.assign(n, glm::dvec3(0.0));
  if (n >= 3) {
    // Natural spline (zero second derivative at the ends): tridiagonal
    // system for the interior second derivatives, Thomas algorithm.
    const size_t m = n - 2;
    std::vector<double> diag(m), upper(m), lower(m);
    std::vector<glm::dvec3> rhs(m);
    for (size_t i = 1; i + 1 < n; ++i) {
      const double h0 = knots_[i] - knots_[i - 1], h1 = knots_[i + 1] - knots_[i];
      lower[i - 1] = h0;
      diag[i - 1] = 2.0 * (h0 + h1);
      upper[i - 1] = h1;
      rhs[i - 1] = 6.0 * ((points_[i + 1] - points_[i]) / h1 - (points_[i] - points_[i - 1]) / h0);
    }
    for (size_t i = 1; i < m; ++i) {
      const double w = lower[i] / diag[i - 1];
      diag[i] -= w * upper[i - 1];
      rhs[i] -= w * rhs[i - 1];
    }
    second_[m] = rhs[m - 1] / diag[m - 1];
    for (size_t i = m - 1; i-- > 0;) second_[i + 1] = (rhs[i] - upper[i] * second_[i + 2]) / diag[i];
  }
  // Arc-length table.
  tableTau_.push_back(0.0);
  tableArc_.push_back(0.0);
  for (size_t i = 0; i + 1 < n; ++i)
    for (int j = 0; j < kSubIntervals; ++j) {
      const double t0 = knots_[i] + (knots_[i + 1] - knots_[i]) * double(j) / kSubIntervals;
      const double t1 = j + 1 == kSubIntervals ? knots_[i + 1]
                                               : knots_[i] + (knots_[i + 1] - knots_[i]) * double(j + 1) / kSubIntervals;
      tableArc_.push_back(tableArc_.back() + speedIntegral(t0, t1));
      tableTau_.push_back(t1);
    }
}

PathSampler::Local PathSampler::locate(double tau) const {
  const size_t n = knots_.size();
  tau = std::clamp(tau, 0.0, knots_.back());
  size_t i = size_t(std::upper_bound(knots_.begin(), knots_.end(), tau) - knots_.begin());
  i = std::clamp<size_t>(i, 1, n - 1) - 1;
  const double h = knots_[i + 1] - knots_[i];
  const double a = (knots_[i + 1] - tau) / h;
  return {i, a, 1.0 - a, h};
}

glm::dvec3 PathSampler::positionAtParameter(double tau) const {
  if (points_.size() < 2) return points_.empty() ? glm::dvec3(0.0) : origin_ + points_.front();
  const Local l = locate(tau);
  const glm::dvec3 rel = l.a * points_[l.span] + l.b * points_[l.span + 1] +
                         ((l.a * l.a * l.a - l.a) * second_[l.span] + (l.b * l.b * l.b - l.b) * second_[l.span + 1]) *
                             (l.h * l.h / 6.0);
  return origin_ + rel;
}

std::pair<glm::dvec3, glm::dvec3> PathSampler::box() const {
  if (points_.empty()) return {glm::dvec3(0.0), glm::dvec3(0.0)};
  glm::dvec3 lo = points_.front(), hi = lo;
  for (size_t i = 0; i + 1 < points_.size(); ++i) {
    const double h = knots_[i + 1] - knots_[i];
    const glm::dvec3 chord = (points_[i + 1] - points_[i]) / h;
    const glm::dvec3 d0 = chord - h / 6.0 * (2.0 * second_[i] + second_[i + 1]);  // dP/dtau at the span's start
    const glm::dvec3 d1 = chord + h / 6.0 * (second_[i] + 2.0 * second_[i + 1]);  // and at its end
    for (const glm::dvec3& b : {points_[i] + h / 3.0 * d0, points_[i + 1] - h / 3.0 * d1, points_[i + 1]}) {
      lo = glm::min(lo, b);
      hi = glm::max(hi, b);
    }
  }
  return {origin_ + lo, origin_ + hi};
}

glm::dvec3 PathSampler::derivative(double tau) const {
  const Local l = locate(tau);
  return (points_[l.span + 1] - points_[l.span]) / l.h - (3.0 * l.a * l.a - 1.0) / 6.0 * l.h * second_[l.span] +
         (3.0 * l.b * l.b - 1.0) / 6.0 * l.h * second_[l.span + 1];
}

glm::dvec3 PathSampler::secondDerivative(double tau) const {
  const Local l = locate(tau);
  return l.a * second_[l.span] + l.b * second_[l.span + 1];
}

double PathSampler::speedIntegral(double tau0, double tau1) const {
  const double half = 0.5 * (tau1 - tau0), mid = 0.5 * (tau0 + tau1);
  double sum = 0.0;
  for (int k = 0; k < 5; ++k) sum += kGaussW[k] * glm::length(derivative(mid + half * kGaussX[k]));
  return sum * half;
}

double PathSampler::parameterAt(double s) const {
  if (points_.size() < 2) return 0.0;
  s = std::clamp(s, 0.0, length());
  size_t j = size_t(std::upper_bound(tableArc_.begin(), tableArc_.end(), s) - tableArc_.begin());
  j = std::clamp<size_t>(j, 1, tableArc_.size() - 1) - 1;
  const double tauA = tableTau_[j], tauB = tableTau_[j + 1];
  const double arcA = tableArc_[j], arcB = tableArc_[j + 1];
  if (arcB <= arcA) return tauA;
  // Newton on F(tau) = arcA + integral(tauA..tau) - s, kept inside the
  // bracket [lo, hi] by bisection when a step would leave it.
  double lo = tauA, hi = tauB;
  double tau = tauA + (s - arcA) / (arcB - arcA) * (tauB - tauA);
  const double tolerance = 1e-13 * std::max(1.0, length());
  for (int it = 0; it < 30; ++it) {
    const double f = arcA + speedIntegral(tauA, tau) - s;
    if (std::abs(f) <= tolerance) break;
    if (f > 0.0) hi = tau; else lo = tau;
    const double speed = glm::length(derivative(tau));
    double next = speed > 0.0 ? tau - f / speed : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    tau = next;
  }
  return tau;
}

glm::dvec3 PathSampler::position(double s) const { return positionAtParameter(parameterAt(s)); }

glm::dvec3 PathSampler::tangent(double s) const {
  if (points_.size() < 2) return glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 d = derivative(parameterAt(s));
  const double len = glm::length(d);
  return len > 0.0 ? d / len : glm::dvec3(0.0, 1.0, 0.0);
}

glm::dvec3 PathSampler::curvatureVector(double s) const {
  if (points_.size() < 3) return glm::dvec3(0.0);
  const double tau = parameterAt(s);
  const glm::dvec3 d1 = derivative(tau), d2 = secondDerivative(tau);
  const double speed2 = glm::dot(d1, d1);
  if (speed2 <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 t = d1 / std::sqrt(speed2);
  return (d2 - glm::dot(d2, t) * t) / speed2;
}

glm::dquat lookRotation(const glm::dvec3& forwardIn) {
  const double len = glm::length(forwardIn);
  const glm::dvec3 f = len > 0.0 ? forwardIn / len : glm::dvec3(0.0, 1.0, 0.0);
  glm::dvec3 right = glm::cross(f, glm::dvec3(0.0, 0.0, 1.0));
  if (glm::length(right) < 1e-9) right = glm::cross(f, glm::dvec3(0.0, 1.0, 0.0));
  right = glm::normalize(right);
  const glm::dvec3 up = glm::cross(right, f);
  // Columns: camera +X, +Y, +Z in world coordinates.
  return glm::normalize(glm::quat_cast(glm::dmat3(right, up, -f)));
}

PathPose evaluatePath(const PathFollow& follow, const PathSampler& sampler, double t,
                      std::optional<glm::dvec3> target) {
  PathPose pose;
  double progress = 0.0, progressRate = 0.0;
  if (auto p = evaluateWithSlope(follow.progress, t)) {
    progress = p->value;
    progressRate = (p->value > 0.0 && p->value < 1.0) ? p->slope : 0.0;  // held at the ends
  }
  const double s = std::clamp(progress, 0.0, 1.0) * sampler.length();
  pose.position = sampler.position(s);
  pose.speed = std::abs(progressRate) * sampler.length();
  const glm::dvec3 travel = sampler.tangent(s) * (progressRate < 0.0 ? -1.0 : 1.0);

  glm::dvec3 forward = travel;
  if (follow.aim == PathAim::Point) target = follow.targetPoint;
  if (follow.aim != PathAim::Tangent) {
    if (target && glm::length(*target - pose.position) > 1e-9) forward = *target - pose.position;
    else pose.aimFallback = true;
  }
  pose.orientation = lookRotation(forward);

  if (follow.bank && follow.maxBankDeg > 0.0) {
    // Lateral acceleration towards the left of the direction of travel.
    const glm::dvec3 left = glm::cross(glm::dvec3(0.0, 0.0, 1.0), travel);
    const double leftLen = glm::length(left);
    if (leftLen > 1e-9) {
      const double aLeft = pose.speed * pose.speed * glm::dot(sampler.curvatureVector(s), left / leftLen);
      const double roll = std::atan(follow.bankScale * aLeft / kGravity);
      const double limit = glm::radians(follow.maxBankDeg);
      const double limited = limit * std::tanh(roll / limit);
      pose.bankDeg = glm::degrees(limited);
      // Rolling left is a negative turn about the forward axis (right hand).
      const glm::dvec3 f = pose.orientation * glm::dvec3(0.0, 0.0, -1.0);
      pose.orientation = glm::normalize(glm::angleAxis(-limited, f) * pose.orientation);
    }
  }
  return pose;
}

}  // namespace hs::sequencer
