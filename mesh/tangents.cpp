#include "mesh/tangents.h"

#include <algorithm>
#include <cmath>

namespace hs::mesh {
namespace {

// A unit vector perpendicular to `n`: the axis least aligned with it, made
// orthogonal (the fallback where UVs give no direction).
glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(a - n * glm::dot(n, a));
}

glm::vec3 safeNormal(const glm::vec3& n) {
  const float l = glm::length(n);
  return std::isfinite(l) && l > 1e-12f ? n / l : glm::vec3(0, 0, 1);
}

}  // namespace

std::vector<glm::vec4> computeTangents(const MeshData& m) {
  const size_t n = m.positions.size();
  std::vector<glm::vec4> out(n);
  const bool hasUvs = m.uvs.size() == n;
  // Per vertex, per handedness (0: +1, 1: -1): the angle-weighted tangent sum and the angle sum.
  std::vector<glm::dvec3> sum[2] = {std::vector<glm::dvec3>(n, glm::dvec3(0.0)), std::vector<glm::dvec3>(n, glm::dvec3(0.0))};
  std::vector<double> weight[2] = {std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  auto normalOf = [&](uint32_t v) { return safeNormal(v < m.normals.size() ? m.normals[v] : glm::vec3(0, 0, 1)); };
  if (hasUvs) {
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const uint32_t idx[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
      if (idx[0] >= n || idx[1] >= n || idx[2] >= n) continue;
      const glm::dvec3 p0(m.positions[idx[0]]), p1(m.positions[idx[1]]), p2(m.positions[idx[2]]);
      const glm::dvec2 w0(m.uvs[idx[0]]), w1(m.uvs[idx[1]]), w2(m.uvs[idx[2]]);
      const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
      const glm::dvec2 d1 = w1 - w0, d2 = w2 - w0;
      const double det = d1.x * d2.y - d2.x * d1.y;
      if (!std::isfinite(det) || std::abs(det) < 1e-20) continue;  // no UV area: no direction
      const glm::dvec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
      const glm::dvec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = idx[c];
        const glm::dvec3 a = glm::dvec3(m.positions[idx[(c + 1) % 3]]) - glm::dvec3(m.positions[v]);
        const glm::dvec3 b = glm::dvec3(m.positions[idx[(c + 2) % 3]]) - glm::dvec3(m.positions[v]);
        const double la = glm::length(a), lb = glm::length(b);
        if (la < 1e-20 || lb < 1e-20) continue;  // a degenerate corner
        const double angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
        if (!std::isfinite(angle) || angle <= 0.0) continue;
        const glm::dvec3 nv(normalOf(v));
        const glm::dvec3 tangent = dPdu - nv * glm::dot(nv, dPdu);
        const double tl = glm::length(tangent);
        if (!std::isfinite(tl) || tl < 1e-20) continue;
        const int side = glm::dot(glm::cross(nv, tangent), dPdv) < 0.0 ? 1 : 0;
        sum[side][v] += tangent / tl * angle;
        weight[side][v] += angle;
      }
    }
  }
  for (size_t v = 0; v < n; ++v) {
    const glm::vec3 nv = normalOf(uint32_t(v));
    const int side = weight[1][v] > weight[0][v] ? 1 : 0;
    glm::dvec3 t = sum[side][v] - glm::dvec3(nv) * glm::dot(glm::dvec3(nv), sum[side][v]);
    const double l = glm::length(t);
    const glm::vec3 tangent = std::isfinite(l) && l > 1e-12 ? glm::vec3(t / l) : anyPerpendicular(nv);
    out[v] = glm::vec4(tangent, side ? -1.0f : 1.0f);
  }
  return out;
}

}  // namespace hs::mesh
