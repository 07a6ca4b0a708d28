#pragma once
// A generated quad-dominant scan of an object (issue 38, "the decimator on
// real quad-dominant scans", second attempt): the hard quad scans
// (quad_scan.h) are height fields on a uniform grid, and the real scan that
// showed our decimator behind meshopt and Blender (32k quads, UV seams, a
// few non-manifold edges, a thin feature collapsed away, 61 flipped faces)
// is not one of those. This one is a closed rock of about 12 m with what a
// remesher or a photogrammetry mesher gives such an object:
//  - density that varies strongly (the quads' spacing around the body
//    varies 12:1 and from pole to pole 4:1, so the sparse region's quads
//    are long and thin: slivers once triangulated), irregular diagonals and
//    jittered points; fans of triangles at the poles;
//  - thin features: five tapering horns (0.2 m to 1.5 cm radius, 2.5 m
//    long, 8 sides, rings 6 cm apart: slivers again) and two thin flakes
//    (double-sided sheets 3 cm thick), as separate shells rooted in the body
//    as a scan's pieces often are, and a sharp ridge one column wide;
//  - a UV atlas of four charts around the body (seams along four meridians
//    and at both poles) and a chart per horn and flake;
//  - three non-manifold fins (a triangle standing on a body edge).
// About 32k quads. Positions in metres around the origin.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "mesh/mesh_data.h"
#include "scan_terrain.h"

namespace hs::bench {

inline hs::mesh::MeshData quadObject(uint64_t seed = 31, int nu = 200, int nv = 150) {
  using namespace detail;
  constexpr double kPi = 3.14159265358979323846;
  hs::mesh::MeshData m;
  // Graded parameters: spacing 1 +- A around (12:1), 1 +- B pole to pole (4:1).
  const double A = 0.85, B = 0.6;
  auto phiOf = [&](double i) { const double t = i / nu; return 2 * kPi * (t + A * std::sin(4 * kPi * t) / (4 * kPi)); };
  auto thetaOf = [&](double j) { const double t = j / nv; return kPi * (t - B * std::sin(2 * kPi * t) / (2 * kPi)); };
  auto dirOf = [](double theta, double phi) {
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  // The rock's radius along a direction: fractal noise, a sharp ridge one
  // column wide (phi at column nu*0.6, on the upper half), millimetre noise.
  const double ridgePhi = phiOf(0.6 * nu);
  auto radius = [&](const glm::dvec3& d, double theta, double phi) {
    double r = 6.0, amp = 0.9, freq = 0.6;
    for (int o = 0; o < 4; ++o, amp *= 0.5, freq *= 2.0)
      r += amp * (valueNoise(d.x * freq * 6, d.y * freq * 6, seed + uint64_t(o)) +
                  valueNoise(d.y * freq * 6 + 17.0, d.z * freq * 6, seed + 10 + uint64_t(o))) * 0.5;
    const double dphi = std::abs(std::remainder(phi - ridgePhi, 2 * kPi));
    if (theta > 0.3 && theta < 1.5) r += 0.8 * std::max(0.0, 1.0 - dphi / 0.02);
    return r;
  };
  auto jitterOf = [&](int i, int j, uint64_t k) { return 0.3 * (2.0 * unit(hash3(i, j, seed + k)) - 1.0); };
  // Vertices of the body: one per grid point and chart (poles: one per chart).
  const int chartCols = nu / 4;
  std::map<std::tuple<int, int, int>, uint32_t> id;
  auto vertex = [&](int i, int j, int chart) {
    const int ii = (j == 0 || j == nv) ? 0 : i % nu;
    auto [it, fresh] = id.try_emplace({ii, j, chart}, uint32_t(m.positions.size()));
    if (fresh) {
      const bool inner = j > 0 && j < nv && i % chartCols != 0;  // seam points stay on their meridian
      const double fi = ii + (inner ? jitterOf(ii, j, 1) : 0.0), fj = j + (j > 0 && j < nv ? jitterOf(ii, j, 2) : 0.0);
      const double theta = thetaOf(fj), phi = phiOf(fi);
      const glm::dvec3 d = dirOf(theta, phi);
      const double noise = 0.002 * (unit(hash3(ii, j, seed + 3)) - 0.5);
      m.positions.push_back(glm::vec3(d * (radius(d, theta, phi) + noise)));
      const double u = double(i - chart * chartCols) / chartCols;
      m.uvs.emplace_back(float(0.25 * chart + 0.01 + 0.23 * u), float(0.02 + 0.6 * double(j) / nv));
    }
    return it->second;
  };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int chart = i / chartCols;
      const uint32_t a = vertex(i, j, chart), b = vertex(i + 1, j, chart), c = vertex(i + 1, j + 1, chart),
                     d = vertex(i, j + 1, chart);
      // Outward faces; the diagonal by a hash (a quad remesher's output
      // triangulated on import has no preferred diagonal).
      if (j == 0) m.indices.insert(m.indices.end(), {a, d, c});
      else if (j == nv - 1) m.indices.insert(m.indices.end(), {a, c, b});
      else if (unit(hash3(i, j, seed + 4)) < 0.5) m.indices.insert(m.indices.end(), {a, c, b, a, d, c});
      else m.indices.insert(m.indices.end(), {a, d, b, b, d, c});
    }
  // Non-manifold fins: a triangle standing on a quad's diagonal.
  for (int k = 0; k < 3; ++k) {
    const int i = nu / 7 + k * nu / 4, j = nv / 3 + k * nv / 6, chart = i / chartCols;
    const uint32_t a = vertex(i, j, chart), c = vertex(i + 1, j + 1, chart);
    const glm::vec3 mid = 0.5f * (m.positions[a] + m.positions[c]);
    m.positions.push_back(mid * 1.03f);
    m.uvs.push_back(m.uvs[a]);
    m.indices.insert(m.indices.end(), {a, c, uint32_t(m.positions.size() - 1)});
  }
  // A swept shell: `ring` (2D, counter-clockwise) swept along `axis` from
  // `base`, scaled by `scale(t)`, capped by a point (`tip`) or by quads
  // between the ring's two long sides (a flake's top).
  auto sweep = [&](const glm::dvec3& base, const glm::dvec3& axis, double length, const std::vector<glm::dvec2>& ring,
                   int rings, auto scale, bool tip, int chart) {
    glm::dvec3 t1 = glm::normalize(glm::cross(axis, std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
    const glm::dvec3 t2 = glm::cross(axis, t1);
    const uint32_t first = uint32_t(m.positions.size());
    const int rn = int(ring.size());
    const glm::vec2 uv0(float(0.02 + 0.14 * chart), 0.66f);
    for (int k = 0; k <= rings; ++k) {
      const double t = double(k) / rings, s = scale(t);
      for (int r = 0; r < rn; ++r) {
        m.positions.push_back(glm::vec3(base + axis * (length * t) + t1 * (s * ring[size_t(r)].x) + t2 * (s * ring[size_t(r)].y)));
        m.uvs.push_back(uv0 + glm::vec2(float(0.12 * r / rn), float(0.3 * t)));
      }
    }
    auto at = [&](int k, int r) { return first + uint32_t(k * rn + (r % rn)); };
    for (int k = 0; k < rings; ++k)
      for (int r = 0; r < rn; ++r)
        m.indices.insert(m.indices.end(), {at(k, r), at(k, r + 1), at(k + 1, r + 1), at(k, r), at(k + 1, r + 1), at(k + 1, r)});
    if (tip) {
      m.positions.push_back(glm::vec3(base + axis * (length + 0.02)));
      m.uvs.push_back(uv0 + glm::vec2(0.06f, 0.31f));
      const uint32_t top = uint32_t(m.positions.size() - 1);
      for (int r = 0; r < rn; ++r) m.indices.insert(m.indices.end(), {at(rings, r), at(rings, r + 1), top});
    } else {
      const int half = rn / 2;  // the ring is one long side (0..half-1) then the other back
      for (int k = 0; k + 1 < half; ++k) {
        const uint32_t a = at(rings, k), b = at(rings, k + 1), c = at(rings, rn - 2 - k), d = at(rings, rn - 1 - k);
        m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
      }
    }
  };
  auto surfaceAt = [&](double theta, double phi) {
    const glm::dvec3 d = dirOf(theta, phi);
    return std::pair{d, radius(d, theta, phi)};
  };
  // Horns: 8 sides, 40 rings, 0.2 m tapering to 1.5 cm, bent a little.
  std::vector<glm::dvec2> octagon;
  for (int s = 0; s < 8; ++s) octagon.push_back({std::cos(2 * kPi * s / 8), std::sin(2 * kPi * s / 8)});
  for (int h = 0; h < 5; ++h) {
    const double theta = 0.5 + 2.1 * unit(hash3(h, 20, seed)), phi = 2 * kPi * unit(hash3(h, 21, seed));
    const auto [d, r] = surfaceAt(theta, phi);
    const glm::dvec3 axis = glm::normalize(d + 0.3 * glm::dvec3(0, 0, 1));
    sweep(d * (r - 0.15), axis, 2.5, octagon, 40, [](double t) { return 0.2 * (1 - t) + 0.015 * t; }, true, h);
  }
  // Flakes: a 2 m x 3 cm section (36 + 1 points a side) 1.5 m high, 12 rings.
  for (int f = 0; f < 2; ++f) {
    const auto [d, r] = surfaceAt(1.2 + 0.8 * f, 1.0 + 2.5 * f);
    std::vector<glm::dvec2> section;
    for (int k = 0; k <= 36; ++k) section.push_back({-1.0 + 2.0 * k / 36, -0.015});
    for (int k = 36; k >= 0; --k) section.push_back({-1.0 + 2.0 * k / 36, 0.015});
    sweep(d * (r - 0.1), d, 1.6, section, 12, [](double) { return 1.0; }, false, 5 + f);
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

}  // namespace hs::bench
