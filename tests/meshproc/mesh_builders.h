#pragma once
// Meshes with known shape for the mesh-processing tests: a gently curved
// grid (optionally with a UV seam along a staircase line), scan defects
// added to it at random, an icosphere, and OBJ writing with exact decimal
// coordinates.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::test {

using hs::mesh::MeshData;

// n x n quads over [0, size]^2, z = amplitude * sin(x) * cos(y) (0 = flat),
// each quad split along its (i,j)-(i+1,j+1) diagonal. With `seam`, a UV
// seam runs through the grid as a staircase of vertical and diagonal edges
// (column seamColumn(n, j) at row j): faces left of it map UV (0.5 x, y),
// faces right of it (0.5 x + 0.5, y), so the vertices on the line exist
// twice, once per side.
inline int seamColumn(int n, int j) { return n / 4 + j / 2; }

inline MeshData curvedGrid(int n, double size, double amplitude, bool seam) {
  MeshData m;
  auto z = [&](double x, double y) { return amplitude * std::sin(x * 3.1 / size) * std::cos(y * 2.3 / size); };
  std::map<std::tuple<int, int, int>, uint32_t> id;
  auto vertex = [&](int i, int j, int side) {
    const auto key = std::make_tuple(i, j, side);
    if (auto it = id.find(key); it != id.end()) return it->second;
    const double x = size * i / n, y = size * j / n;
    m.positions.emplace_back(float(x), float(y), float(z(x, y)));
    m.uvs.emplace_back(float(0.5 * i / n + (side ? 0.5 : 0.0)), float(double(j) / n));
    return id[key] = uint32_t(m.positions.size() - 1);
  };
  // Which side of the seam a triangle with this centroid (grid units) is on.
  auto sideOf = [&](double cx, double cy) {
    if (!seam) return 0;
    const int j = std::min(int(cy), n - 1);
    const double line = seamColumn(n, j) + (seamColumn(n, j + 1) - seamColumn(n, j)) * (cy - j);
    return cx > line ? 1 : 0;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int s1 = sideOf(i + 2.0 / 3.0, j + 1.0 / 3.0), s2 = sideOf(i + 1.0 / 3.0, j + 2.0 / 3.0);
      m.indices.insert(m.indices.end(), {vertex(i, j, s1), vertex(i + 1, j, s1), vertex(i + 1, j + 1, s1)});
      m.indices.insert(m.indices.end(), {vertex(i, j, s2), vertex(i + 1, j + 1, s2), vertex(i, j + 1, s2)});
    }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  hs::mesh::computeVertexNormals(m);
  return m;
}

// A quad-dominant scan patch: n x n quads over [0, size]^2, each cut along
// the same diagonal as an importer triangulates quads, over rolling
// ground z = relief(x, y) (curved along every open border too) with scan
// noise of +-noise/2 per vertex from a fixed hash (the same mesh every
// run). No UVs: the borders are the polylines.
inline double quadScanRelief(double x, double y, double size, double amplitude) {
  return amplitude * (std::sin(x * 9.0 / size) + 0.6 * std::cos(y * 7.0 / size + 0.5));
}

inline MeshData quadScanPatch(int n, double size, double amplitude, double noise) {
  MeshData m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, y = size * j / n;
      uint32_t h = uint32_t(i) * 73856093u ^ uint32_t(j) * 19349663u;
      h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
      const double jitter = noise * (double(h & 0xffffu) / 65535.0 - 0.5);
      m.positions.emplace_back(float(x), float(y), float(quadScanRelief(x, y, size, amplitude) + jitter));
    }
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.indices.insert(m.indices.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  hs::mesh::computeVertexNormals(m);
  return m;
}

// Icosahedron subdivided `levels` times onto a sphere of `radius`
// (20 * 4^levels faces).
inline MeshData icosphere(int levels, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& v : p) v = glm::normalize(v);
  std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
                             7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7,
                             9, 8, 1};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(glm::normalize(p[a] + p[b]));
      return mid[key] = uint32_t(p.size() - 1);
    };
    std::vector<uint32_t> g;
    for (size_t i = 0; i < f.size(); i += 3) {
      const uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      g.insert(g.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(g);
  }
  MeshData m;
  for (const auto& v : p) m.positions.emplace_back(glm::vec3(v * radius));
  m.indices = f;
  m.submeshes.push_back({0, uint32_t(f.size()), -1});
  hs::mesh::computeVertexNormals(m);
  return m;
}

// The icosphere of 20480 faces and radius 10 with a few bumps (so
// simplifying costs some error): the cluster hierarchy tests' closed surface.
inline MeshData bumpySphere() {
  MeshData m = icosphere(5, 10.0);
  for (glm::vec3& p : m.positions) {
    const glm::vec3 n = glm::normalize(p);
    p = n * (10.0f + 0.4f * std::sin(5.0f * n.x) * std::cos(4.0f * n.y) + 0.2f * std::sin(9.0f * n.z));
  }
  return m;
}

// The bumps of bumpySphere() on a unit direction, as a radius.
inline double bumpyRadius(const glm::dvec3& n) {
  return 10.0 + 0.4 * std::sin(5.0 * n.x) * std::cos(4.0 * n.y) + 0.2 * std::sin(9.0 * n.z);
}

// The same bumpy sphere sampled the way a remesher or a photogrammetry
// mesher can leave a scan: a latitude-longitude grid of nu x nv quads whose
// spacing around varies by (1 + grading) : (1 - grading) (0.85: 12:1), so
// the sparse side's quads are long and thin (triangles of quality well
// under 0.1), with fans at the poles.
inline MeshData gradedBumpySphere(int nu, int nv, double grading) {
  const double pi = 3.14159265358979323846;
  MeshData m;
  auto add = [&](double theta, double phi) {
    const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    m.positions.emplace_back(glm::vec3(n * bumpyRadius(n)));
  };
  add(0.0, 0.0);  // north pole: vertex 0
  for (int j = 1; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double t = double(i) / nu;
      add(pi * j / nv, 2 * pi * (t + grading * std::sin(2 * pi * t) / (2 * pi)));
    }
  add(pi, 0.0);  // south pole: the last vertex
  const uint32_t south = uint32_t(m.positions.size() - 1);
  auto ring = [&](int j, int i) { return uint32_t(1 + (j - 1) * nu + (i % nu)); };
  for (int i = 0; i < nu; ++i) {
    m.indices.insert(m.indices.end(), {0u, ring(1, i), ring(1, i + 1)});
    m.indices.insert(m.indices.end(), {south, ring(nv - 1, i + 1), ring(nv - 1, i)});
    for (int j = 1; j + 1 < nv; ++j) {
      const uint32_t a = ring(j, i), b = ring(j, i + 1), c = ring(j + 1, i + 1), d = ring(j + 1, i);
      m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
    }
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  hs::mesh::computeVertexNormals(m);
  return m;
}

// Writes `m` as OBJ with positions origin + local + `offset` printed with
// `decimals` digits (20 prints a dyadic fraction exactly), Z-up as stored.
inline void writeObj(const std::string& path, const MeshData& m, glm::dvec3 offset = glm::dvec3(0.0),
                     int decimals = 9, bool withUv = true) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  for (const auto& p : m.positions) {
    const glm::dvec3 w = m.origin + glm::dvec3(p) + offset;
    std::fprintf(f, "v %.*f %.*f %.*f\n", decimals, w.x, decimals, w.y, decimals, w.z);
  }
  const bool uv = withUv && m.uvs.size() == m.positions.size();
  if (uv)
    for (const auto& t : m.uvs) std::fprintf(f, "vt %.9g %.9g\n", double(t.x), 1.0 - double(t.y));
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    if (uv)
      std::fprintf(f, "f %u/%u %u/%u %u/%u\n", m.indices[i] + 1, m.indices[i] + 1, m.indices[i + 1] + 1,
                   m.indices[i + 1] + 1, m.indices[i + 2] + 1, m.indices[i + 2] + 1);
    else
      std::fprintf(f, "f %u %u %u\n", m.indices[i] + 1, m.indices[i + 1] + 1, m.indices[i + 2] + 1);
  }
  std::fclose(f);
}

// One scan defect on `in` (a copy of `grid`, whose faces are picked by
// `rng`): 0 a fin (a third face on an edge), 1 a fin the other way round,
// 2 a triangle touching the surface at one vertex (a bow-tie), 3 a face
// stored twice, 4 a face twice the other way round, 5 a loose triangle
// above the surface, 6 a two-sided flap (a triangle and its reverse on
// vertices of their own), 7 a face that repeats a vertex, 8 a fin of zero
// area (its free vertex at the edge's midpoint), 9 a face whose corner is
// an unwelded copy of the surface's vertex, 10 a splinter: a fin whose
// free vertex is the next float after one end of its edge. New vertices
// of kinds 0-6 sit 0.6 above the surface, with UV (0.25, 0.25).
inline void addDefect(MeshData& in, const MeshData& grid, int kind, std::mt19937& rng) {
  auto addVertex = [&](const glm::vec3& p) {
    in.positions.push_back(p);
    if (!in.uvs.empty()) in.uvs.push_back({0.25f, 0.25f});
    if (!in.normals.empty()) in.normals.push_back({0, 0, 1});
    return uint32_t(in.positions.size() - 1);
  };
  const size_t f = rng() % grid.triangleCount();
  const uint32_t k = rng() % 3;
  const uint32_t a = grid.indices[f * 3 + k], b = grid.indices[f * 3 + (k + 1) % 3],
                 c = grid.indices[f * 3 + (k + 2) % 3];
  const glm::vec3 up = grid.positions[a] + glm::vec3(0.05f, 0.1f, 0.6f);
  auto add = [&](std::initializer_list<uint32_t> ids) { in.indices.insert(in.indices.end(), ids); };
  switch (kind) {
    case 0: add({a, b, addVertex(up)}); break;
    case 1: add({b, a, addVertex(up)}); break;
    case 2: {
      const uint32_t x = addVertex(up), y = addVertex(up + glm::vec3(0.2f, 0.0f, 0.0f));
      add({a, x, y});
      break;
    }
    case 3: add({a, b, c}); break;
    case 4: add({a, c, b}); break;
    case 5:
    case 6: {
      const uint32_t x = addVertex(up), y = addVertex(up + glm::vec3(0.3f, 0.0f, 0.0f)),
                     z = addVertex(up + glm::vec3(0.0f, 0.3f, 0.0f));
      add({x, y, z});
      if (kind == 6) add({x, z, y});
      break;
    }
    case 7: add({a, a, b}); break;
    case 8: add({a, b, addVertex(0.5f * (grid.positions[a] + grid.positions[b]))}); break;
    case 9: add({addVertex(grid.positions[a]), b, c}); break;
    case 10: {
      const glm::vec3 p = grid.positions[a];
      add({a, b, addVertex({std::nextafter(p.x, p.x + 1.0f), p.y, p.z})});
      break;
    }
  }
  if (!in.submeshes.empty()) in.submeshes.back().indexCount = uint32_t(in.indices.size()) - in.submeshes.back().firstIndex;
}

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(text.data(), std::streamsize(text.size()));
}

inline std::vector<glm::dvec3> world(const MeshData& m) {
  std::vector<glm::dvec3> w;
  for (const auto& p : m.positions) w.push_back(m.origin + glm::dvec3(p));
  return w;
}

}  // namespace hs::test
