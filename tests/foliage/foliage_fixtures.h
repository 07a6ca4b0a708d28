#pragma once
// Terrains, meshes and stores the foliage suites share.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <functional>

#include "foliage/store.h"
#include "foliage/surface.h"
#include "foliage/tools.h"
#include "mesh/mesh_data.h"
#include "terrain/terrain.h"

namespace fx {

using namespace hs::foliage;
namespace ht = hs::terrain;

// A terrain of n x n samples, `spacing` metres apart, at `origin`, with
// heights h(local x, local y).
inline ht::Terrain terrain(int n, double spacing, const glm::dvec3& origin,
                           const std::function<double(double, double)>& h) {
  ht::HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = glm::dvec2(spacing * (n - 1));
  d.origin = origin;
  auto r = ht::Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  ht::Terrain t = r.take();
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) t.height.heights().set(x, y, float(h(x * spacing, y * spacing)));
  t.height.updateAllBounds();
  return t;
}

// A grid mesh over [0, size]^2 (local), z = h(x, y), placed at `origin`.
inline hs::mesh::MeshData gridMesh(int n, double size, const glm::dvec3& origin,
                                   const std::function<double(double, double)>& h) {
  hs::mesh::MeshData m;
  m.origin = origin;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const double px = size * x / n, py = size * y / n;
      m.positions.emplace_back(float(px), float(py), float(h(px, py)));
    }
  auto v = [&](int x, int y) { return uint32_t(y * (n + 1) + x); };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      m.indices.insert(m.indices.end(), {v(x, y), v(x + 1, y), v(x + 1, y + 1)});
      m.indices.insert(m.indices.end(), {v(x, y), v(x + 1, y + 1), v(x, y + 1)});
    }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  hs::mesh::computeVertexNormals(m);
  return m;
}

inline FoliageType type(const std::string& name, double densityPerHa, double spacing) {
  FoliageType t;
  t.name = name;
  t.mesh = name + " mesh";
  t.densityPerHa = densityPerHa;
  t.spacing = spacing;
  return t;
}

inline uint16_t addType(FoliageStore& s, const FoliageType& t) {
  std::vector<std::string> m;
  const int i = s.addType(t, m);
  if (i < 0) qFatal("addType: %s", m.empty() ? "?" : m[0].c_str());
  return uint16_t(i);
}

// Every instance with its bits: what "exactly the same" compares.
struct Snapshot {
  std::vector<Instance> inst;
  uint32_t nextId = 0;
};
inline Snapshot snapshot(const FoliageStore& s) {
  Snapshot sn{s.allInstances(), s.nextId()};
  std::sort(sn.inst.begin(), sn.inst.end(), [](const Instance& a, const Instance& b) { return a.id < b.id; });
  return sn;
}
inline bool same(const Snapshot& a, const Snapshot& b) {
  if (a.nextId != b.nextId || a.inst.size() != b.inst.size()) return false;
  for (size_t i = 0; i < a.inst.size(); ++i) {
    const Instance &x = a.inst[i], &y = b.inst[i];
    if (x.id != y.id || x.type != y.type || x.surface != y.surface || x.position != y.position ||
        std::memcmp(&x.rotation, &y.rotation, sizeof x.rotation) != 0 || x.scale != y.scale)
      return false;
  }
  return true;
}

}  // namespace fx
