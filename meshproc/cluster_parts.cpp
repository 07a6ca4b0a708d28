#include "meshproc/cluster_parts.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "meshproc/position_key.h"

namespace hs::mesh {

using Triangles = std::vector<uint32_t>;

std::vector<uint32_t> weldForClusters(const std::vector<glm::vec3>& positions, const std::vector<glm::vec2>& uvsIn,
                                      const std::vector<uint32_t>& indices, std::vector<glm::vec3>& pool,
                                      std::vector<glm::vec2>& poolUvs) {
  const bool uvs = uvsIn.size() == positions.size() && !uvsIn.empty();
  std::unordered_map<uint64_t, std::vector<uint32_t>> byKey;
  std::vector<uint32_t> remap(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    const glm::vec2 uv = uvs ? uvsIn[i] : glm::vec2(0.0f);
    std::vector<uint32_t>& same = byKey[positionKey(p)];
    uint32_t at = UINT32_MAX;
    for (uint32_t s : same)
      if (pool[s] == p && (!uvs || poolUvs[s] == uv)) at = s;
    if (at == UINT32_MAX) {
      at = uint32_t(pool.size());
      pool.push_back(p);
      if (uvs) poolUvs.push_back(uv);
      same.push_back(at);
    }
    remap[i] = at;
  }
  std::vector<uint32_t> tris;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = remap[indices[t]], b = remap[indices[t + 1]], c = remap[indices[t + 2]];
    if (a != b && b != c && a != c) tris.insert(tris.end(), {a, b, c});  // welded to a sliver of none
  }
  return tris;
}

LodSphere sphereOf(const std::vector<glm::vec3>& pool, const uint32_t* indices, size_t count) {
  if (count == 0) return {};
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (size_t i = 0; i < count; ++i) {
    lo = glm::min(lo, pool[indices[i]]);
    hi = glm::max(hi, pool[indices[i]]);
  }
  LodSphere s{0.5f * (lo + hi), 0.0f};
  for (size_t i = 0; i < count; ++i) s.radius = std::max(s.radius, glm::length(pool[indices[i]] - s.centre));
  return s;
}

float coordinateSlack(const LodSphere& s) {
  const float scale = std::max({std::abs(s.centre.x), std::abs(s.centre.y), std::abs(s.centre.z)}) + s.radius;
  return scale * 1e-6f;  // eight units in the last place (2^-23 each)
}

LodSphere merged(const LodSphere& a, const LodSphere& b) {
  const glm::vec3 d = b.centre - a.centre;
  const float dist = glm::length(d);
  if (dist + b.radius <= a.radius) return a;
  if (dist + a.radius <= b.radius) return b;
  LodSphere s;
  s.radius = 0.5f * (dist + a.radius + b.radius);
  s.centre = a.centre + d * ((s.radius - a.radius) / std::max(dist, 1e-30f));
  // Float rounding must not leave either outside: the centre is off by up
  // to a few units in the last place of the coordinates, which far from
  // the origin (a small sphere 2 km out) is more than a share of the radius.
  s.radius = s.radius * (1.0f + 1e-6f) + coordinateSlack(s);
  return s;
}

std::vector<Triangles> meshletsOf(const std::vector<glm::vec3>& pool, const Triangles& tris,
                                  const ClusterOptions& o) {
  std::unordered_map<uint32_t, uint32_t> local;
  std::vector<uint32_t> toPool;
  std::vector<float> xyz;
  std::vector<uint32_t> idx(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    auto [it, added] = local.try_emplace(tris[i], uint32_t(toPool.size()));
    if (added) {
      toPool.push_back(tris[i]);
      const glm::vec3& p = pool[tris[i]];
      xyz.insert(xyz.end(), {p.x, p.y, p.z});
    }
    idx[i] = it->second;
  }
  const size_t maxTri = std::clamp<size_t>(o.maxTriangles / 4 * 4, 4, 512);
  const size_t maxVert = std::clamp<size_t>(o.maxVertices, 3, 255);
  std::vector<meshopt_Meshlet> meshlets(meshopt_buildMeshletsBound(idx.size(), maxVert, maxTri));
  std::vector<unsigned> verts(meshlets.size() * maxVert);
  std::vector<unsigned char> corners(meshlets.size() * maxTri * 3);
  const size_t n = meshopt_buildMeshlets(meshlets.data(), verts.data(), corners.data(), idx.data(), idx.size(),
                                         xyz.data(), toPool.size(), sizeof(float) * 3, maxVert, maxTri, 0.0f);
  std::vector<Triangles> out(n);
  for (size_t m = 0; m < n; ++m) {
    const meshopt_Meshlet& ml = meshlets[m];
    for (unsigned t = 0; t < ml.triangle_count * 3; ++t)
      out[m].push_back(toPool[verts[ml.vertex_offset + corners[ml.triangle_offset + t]]]);
  }
  return out;
}

}  // namespace hs::mesh
