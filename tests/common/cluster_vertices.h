#pragma once
// A clustered asset's vertices of one level, in world metres, and the
// distance from a point to the nearest of them: what the 3D Tiles tests
// compare a tileset's vertices against.
#include <QtGlobal>

#include <algorithm>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/cluster_asset.h"

namespace hs::test {

// Every vertex of the clusters of `level`, sorted by x (for nearestOf).
inline std::vector<glm::dvec3> clusterLevelVertices(const scene::ClusterAsset& a, uint32_t level) {
  std::vector<glm::dvec3> out;
  for (uint32_t p = 0; p < a.index.pageCount; ++p) {
    std::string error;
    auto page = a.loadPage(p, "test", error);
    if (!page) qFatal("%s", error.c_str());
    for (const mesh::PageCluster& c : *page)
      if (a.index.clusters[c.cluster].level == level)
        for (const glm::vec3& v : c.positions) out.push_back(a.index.origin + glm::dvec3(v));
  }
  std::sort(out.begin(), out.end(), [](const glm::dvec3& l, const glm::dvec3& r) { return l.x < r.x; });
  return out;
}

// The distance from `q` to the nearest of `sorted` (sorted by x) within
// `reach` in x; 1e300 when none is that close.
inline double nearestOf(const std::vector<glm::dvec3>& sorted, const glm::dvec3& q, double reach) {
  double best = 1e300;
  auto it = std::lower_bound(sorted.begin(), sorted.end(), q.x - reach,
                             [](const glm::dvec3& a, double x) { return a.x < x; });
  for (; it != sorted.end() && it->x <= q.x + reach; ++it) best = std::min(best, glm::length(*it - q));
  return best;
}

}  // namespace hs::test
