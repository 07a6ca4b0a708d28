#include "particles/collider.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hs::particles {

HeightFieldCollider::HeightFieldCollider(std::function<double(double, double)> height,
                                         std::function<glm::dvec3(double, double)> normal, double spacing)
    : height_(std::move(height)), normal_(std::move(normal)), spacing_(spacing > 0.0 ? spacing : 0.25) {}

glm::dvec3 HeightFieldCollider::normal(double x, double y) const {
  if (normal_) return glm::normalize(normal_(x, y));
  const double e = spacing_ * 0.01;
  const double dx = (height_(x + e, y) - height_(x - e, y)) / (2.0 * e);
  const double dy = (height_(x, y + e) - height_(x, y - e)) / (2.0 * e);
  return glm::normalize(glm::dvec3(-dx, -dy, 1.0));
}

std::optional<Hit> HeightFieldCollider::raycast(const glm::dvec3& from, const glm::dvec3& to) const {
  const glm::dvec3 d = to - from;
  auto above = [&](double s) {
    const glm::dvec3 p = from + d * s;
    return p.z - height_(p.x, p.y);
  };
  const double f0 = above(0.0);
  if (f0 < 0.0) {
    Hit h;
    h.fraction = 0.0;
    h.point = {from.x, from.y, height_(from.x, from.y)};
    h.normal = normal(from.x, from.y);
    return h;
  }
  const double horizontal = std::sqrt(d.x * d.x + d.y * d.y);
  const int samples = int(std::min(1e6, std::ceil(horizontal / spacing_))) + 1;
  double s0 = 0.0, a0 = f0;
  for (int i = 1; i <= samples; ++i) {
    const double s1 = double(i) / double(samples);
    const double a1 = above(s1);
    if (a1 < 0.0 || (a1 == 0.0 && a0 > 0.0)) {
      // Bisect the sign change to 1e-6 m along the segment (and at most 60 halvings).
      double lo = s0, hi = s1;
      const double len = glm::length(d);
      for (int it = 0; it < 60 && (hi - lo) * len > 1e-7; ++it) {
        const double m = 0.5 * (lo + hi);
        if (above(m) > 0.0) lo = m;
        else hi = m;
      }
      Hit h;
      h.fraction = hi;
      const glm::dvec3 p = from + d * hi;
      h.point = {p.x, p.y, std::max(p.z, height_(p.x, p.y))};
      h.normal = normal(p.x, p.y);
      return h;
    }
    s0 = s1;
    a0 = a1;
  }
  return std::nullopt;
}

TriangleMeshCollider::TriangleMeshCollider(std::vector<glm::dvec3> corners) : corners_(std::move(corners)) {}

std::optional<Hit> TriangleMeshCollider::raycast(const glm::dvec3& from, const glm::dvec3& to) const {
  const glm::dvec3 d = to - from;
  std::optional<Hit> best;
  for (size_t i = 0; i + 2 < corners_.size(); i += 3) {
    const glm::dvec3 &a = corners_[i], &b = corners_[i + 1], &c = corners_[i + 2];
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300) continue;
    const double inv = 1.0 / det;
    const glm::dvec3 s = from - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, q) * inv;
    if (t < 0.0 || t > 1.0) continue;
    if (best && t >= best->fraction) continue;
    Hit h;
    h.fraction = t;
    h.point = a + u * e1 + v * e2;
    glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
    if (glm::dot(n, d) > 0.0) n = -n;
    h.normal = n;
    best = h;
  }
  return best;
}

std::optional<Hit> nearestHit(const std::vector<const Collider*>& colliders, const glm::dvec3& from,
                              const glm::dvec3& to) {
  std::optional<Hit> best;
  for (const Collider* c : colliders) {
    if (!c) continue;
    std::optional<Hit> h = c->raycast(from, to);
    if (h && (!best || h->fraction < best->fraction)) best = h;
  }
  return best;
}

}  // namespace hs::particles
