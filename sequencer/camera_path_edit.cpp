#include "sequencer/camera_path_edit.h"

#include <cmath>

namespace hs::sequencer {

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

ScalarTrack constantSpeedProgress(double t0, double t1, Ease ease) {
  ScalarKey a, b;
  a.time = t0;
  a.value = 0.0;
  // Linear, so the share travelled grows in proportion to time: with the
  // sampler's arc-length parameterisation that is constant speed.
  a.interpolation = Interpolation::Linear;
  a.ease = ease;
  b.time = t1;
  b.value = 1.0;
  b.interpolation = Interpolation::Linear;
  return ScalarTrack{"path.progress", {a, b}};
}

PathFollow makePathFollow(std::vector<glm::dvec3> points, double t0, double t1) {
  PathFollow f;
  f.path.points = std::move(points);
  f.progress = constantSpeedProgress(t0, t1);
  return f;
}

glm::dvec3 pointAfter(const CameraPath& path, size_t index) {
  const std::vector<glm::dvec3>& p = path.points;
  if (p.empty()) return glm::dvec3(0.0);
  if (p.size() == 1) return p[0] + glm::dvec3(0.0, kDefaultPathLength, 0.0);
  const PathSampler sampler(p);
  if (index + 1 < p.size()) {
    // The sampler's knots are cumulative chord lengths (duplicates add 0).
    double knot = 0.0;
    for (size_t i = 1; i <= index; ++i) knot += glm::length(p[i] - p[i - 1]);
    return sampler.positionAtParameter(knot + 0.5 * glm::length(p[index + 1] - p[index]));
  }
  double span = glm::length(p.back() - p[p.size() - 2]);
  if (!(span > 0.0)) span = kDefaultPathLength;
  return p.back() + sampler.tangent(sampler.length()) * span;
}

std::optional<std::string> pathProblem(const PathFollow& f) {
  const std::vector<glm::dvec3>& p = f.path.points;
  for (size_t i = 0; i < p.size(); ++i)
    if (!finite(p[i])) return "point " + std::to_string(i + 1) + " is not a finite position";
  if (p.size() < 2) return "a path needs at least two points (it has " + std::to_string(p.size()) + ")";
  if (!(PathSampler(p).length() > 0.0)) return "the path's points are all in one place: it has no length";
  if (!finite(f.targetPoint)) return "the look-at point is not a finite position";
  if (!(f.maxBankDeg > 0.0 && f.maxBankDeg <= 90.0))
    return "the banking limit must be above 0 and at most 90 degrees";
  if (!(f.bankScale > 0.0 && std::isfinite(f.bankScale))) return "the banking strength must be a positive number";
  for (const ScalarKey& k : f.progress.keys)
    if (!std::isfinite(k.time) || !std::isfinite(k.value)) return "a progress key is not a finite number";
  return std::nullopt;
}

}  // namespace hs::sequencer
