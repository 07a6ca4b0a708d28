#pragma once
// The cut one error bound takes everywhere, for the hierarchy as built
// (Cluster) and as paged (ClusterIndexEntry): both have error,
// parentError and triangleCount. Declared in cluster_hierarchy.h
// (uniformClusterCut) and cluster_cut.h (uniformIndexCut).
#include <algorithm>
#include <cstdint>
#include <vector>

namespace hs::mesh {

template <class C>
std::vector<uint32_t> uniformCutOf(const std::vector<C>& clusters, size_t maxTriangles, float* errorOut) {
  auto cutAt = [&](float e) {
    std::vector<uint32_t> cut;
    for (uint32_t i = 0; i < clusters.size(); ++i)
      if (clusters[i].error <= e && clusters[i].parentError > e) cut.push_back(i);
    return cut;
  };
  // The cut's triangles fall as the error grows: search the errors clusters
  // were made with (the only places the cut changes).
  std::vector<float> errors{0.0f};
  for (const C& c : clusters) errors.push_back(c.error);
  std::sort(errors.begin(), errors.end());
  errors.erase(std::unique(errors.begin(), errors.end()), errors.end());
  auto triangles = [&](float e) {
    size_t n = 0;
    for (const C& c : clusters)
      if (c.error <= e && c.parentError > e) n += c.triangleCount;
    return n;
  };
  size_t lo = 0, hi = errors.size() - 1;  // the largest error: the roots
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (triangles(errors[mid]) <= maxTriangles) hi = mid;
    else lo = mid + 1;
  }
  if (errorOut) *errorOut = errors[lo];
  return cutAt(errors[lo]);
}

}  // namespace hs::mesh
