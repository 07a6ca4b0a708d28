#include "meshproc/cluster_hierarchy.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

#include "core/parallel.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/cluster_levels.h"
#include "meshproc/cluster_parts.h"
#include "meshproc/position_key.h"
#include "meshproc/uniform_cut.h"

namespace hs::mesh {
namespace {

using Triangles = std::vector<uint32_t>;  // three indices a triangle

// What simplifying one group gave, before its new vertices join the pool.
struct GroupResult {
  bool simplified = false;
  float error = 0.0f;
  std::vector<glm::vec3> positions;  // the decimated group's vertices
  std::vector<glm::vec2> uvs;        // and their UVs (none without)
  std::vector<int64_t> poolIndex;    // per vertex: the pool entry it is (same position), or -1: new
  std::vector<Triangles> clusters;   // local vertex indices
};

GroupResult simplifyGroup(const std::vector<glm::vec3>& pool, const std::vector<glm::vec2>& poolUvs,
                          const Triangles& tris, const std::vector<uint8_t>& locked, const ClusterOptions& o) {
  GroupResult r;
  MeshData m;
  std::unordered_map<uint32_t, uint32_t> local;
  std::vector<uint32_t> toPool;
  for (uint32_t v : tris) {
    auto [it, added] = local.try_emplace(v, uint32_t(toPool.size()));
    if (added) toPool.push_back(v);
    m.indices.push_back(it->second);
  }
  DecimateOptions d;
  for (uint32_t v : toPool) {
    m.positions.push_back(pool[v]);
    if (!poolUvs.empty()) m.uvs.push_back(poolUvs[v]);
    d.lockedVertices.push_back(locked[v]);
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  const size_t before = m.triangleCount();
  d.targetTriangles = std::max<size_t>(1, before / 2);
  d.copyTextures = false;
  d.threads = 1;  // groups run in parallel
  const DecimateResult dr = decimate(m, d);
  if (!dr.ok() || double(dr.mesh.triangleCount()) > (1.0 - o.minReduction) * double(before)) return r;
  r.simplified = true;
  // The group's own error: a certified upper bound of the Hausdorff
  // distance between its triangles before and after (meshproc/
  // error_metrics.h), not the quadric's estimate, which can fall short.
  r.error = float(dr.report.maxEstimatedError);
  if (o.certifyErrors) {
    // The vertices' distances both ways are a lower bound; faces are then
    // bounded from their corners and cut where the bound is more than a
    // quarter above it (meshproc/error_metrics.h): a true upper bound,
    // at most a quarter loose where six levels of cutting sufficed.
    ErrorOptions eo;
    eo.threads = 1;
    const ErrorMeter meter(m, eo);
    const ErrorMeter::VertexCheck check = meter.checkVertices(dr.mesh);
    const HausdorffBound bound = meter.hausdorffUpperBound(dr.mesh, check.hausdorff(), 0.25, 6, &check);
    r.error = std::max(r.error, float(bound.upper));
  }
  r.positions = dr.mesh.positions;
  if (!poolUvs.empty()) r.uvs = dr.mesh.uvs;
  // An output vertex the same as an input one (locked, or left where it
  // was) is that pool entry: clusters of two levels share it.
  std::unordered_multimap<uint64_t, uint32_t> byPosition;
  for (uint32_t v : toPool) byPosition.emplace(positionKey(pool[v]), v);
  r.poolIndex.assign(r.positions.size(), -1);
  for (size_t i = 0; i < r.positions.size(); ++i) {
    const auto [first, last] = byPosition.equal_range(positionKey(r.positions[i]));
    for (auto it = first; it != last; ++it)
      if (pool[it->second] == r.positions[i] && (poolUvs.empty() || poolUvs[it->second] == r.uvs[i]))
        r.poolIndex[i] = it->second;
  }
  // Cut into clusters on a scratch pool of the group's own vertices.
  Triangles out(dr.mesh.indices.begin(), dr.mesh.indices.end());
  r.clusters = meshletsOf(r.positions, out, o);
  return r;
}

// Neighbouring clusters in groups of up to `size`, deterministically:
// clusters in order of their centre along a Morton curve; each group grown
// from the first ungrouped one by the ungrouped neighbour sharing the most
// edges with it.
std::vector<std::vector<uint32_t>> groupClusters(const ClusterHierarchy& h, const std::vector<uint32_t>& active,
                                                 size_t size) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edgeOwners;  // ordered: deterministic
  for (uint32_t a = 0; a < active.size(); ++a) {
    const Cluster& c = h.clusters[active[a]];
    for (uint32_t t = 0; t < c.triangleCount; ++t)
      for (int k = 0; k < 3; ++k) {
        uint32_t u = h.indices[c.firstIndex + t * 3 + k], v = h.indices[c.firstIndex + t * 3 + (k + 1) % 3];
        if (u > v) std::swap(u, v);
        std::vector<uint32_t>& owners = edgeOwners[{u, v}];
        if (owners.empty() || owners.back() != a) owners.push_back(a);
      }
  }
  std::vector<std::map<uint32_t, uint32_t>> shared(active.size());  // neighbour -> edges shared
  for (const auto& [edge, owners] : edgeOwners)
    for (uint32_t x : owners)
      for (uint32_t y : owners)
        if (x != y) ++shared[x][y];
  // Morton order of the bounds' centres over the active set's box.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (uint32_t id : active) {
    lo = glm::min(lo, h.clusters[id].bounds.centre);
    hi = glm::max(hi, h.clusters[id].bounds.centre);
  }
  auto spread = [](uint32_t x) {
    uint64_t v = x & 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  std::vector<std::pair<uint64_t, uint32_t>> order;
  for (uint32_t a = 0; a < active.size(); ++a) {
    const glm::vec3 u = (h.clusters[active[a]].bounds.centre - lo) / glm::max(hi - lo, glm::vec3(1e-20f));
    const glm::uvec3 q(glm::clamp(u, 0.0f, 1.0f) * 2097151.0f);
    order.push_back({spread(q.x) | spread(q.y) << 1 | spread(q.z) << 2, a});
  }
  std::sort(order.begin(), order.end());
  std::vector<int> groupOf(active.size(), -1);
  std::vector<std::vector<uint32_t>> groups;
  for (const auto& [key, a] : order) {
    if (groupOf[a] >= 0) continue;
    std::vector<uint32_t> g{a};
    groupOf[a] = int(groups.size());
    while (g.size() < size) {
      std::map<uint32_t, uint32_t> candidates;
      for (uint32_t m : g)
        for (const auto& [n, edges] : shared[m])
          if (groupOf[n] < 0) candidates[n] += edges;
      if (candidates.empty()) break;
      const auto best = std::max_element(candidates.begin(), candidates.end(),
                                         [](const auto& x, const auto& y) { return x.second < y.second; });
      groupOf[best->first] = int(groups.size());
      g.push_back(best->first);
    }
    groups.push_back(std::move(g));
  }
  for (auto& g : groups)
    for (uint32_t& a : g) a = active[a];  // to cluster ids
  return groups;
}

}  // namespace

void addCluster(ClusterHierarchy& h, const Triangles& tris, uint32_t level, const LodSphere& lodBounds, float error) {
  Cluster c;
  c.firstIndex = uint32_t(h.indices.size());
  c.triangleCount = uint32_t(tris.size() / 3);
  c.level = level;
  h.indices.insert(h.indices.end(), tris.begin(), tris.end());
  c.bounds = sphereOf(h.positions, tris.data(), tris.size());
  c.lodBounds = level == 0 ? c.bounds : lodBounds;
  c.error = error;
  h.clusters.push_back(c);
}

LevelStep simplifyLevel(ClusterHierarchy& h, const std::vector<uint32_t>& active, uint32_t level,
                        const ClusterOptions& options, const ExternalLock& externalLock, const GroupedHook& onGrouped,
                        ClusterBuildReport& rep, const Progress* progress) {
  LevelStep step;
  const unsigned threads = resolveThreads(options.threads);
  const std::vector<std::vector<uint32_t>> groups = groupClusters(h, active, std::max<size_t>(2, options.groupSize));
  if (onGrouped) onGrouped(groups);
  // Locked: a vertex whose position two groups' triangles use (their
  // shared border; by position, so both sides of a UV seam along it), and
  // one the caller says is shared with what lies outside (`externalLock`).
  // Positions compared by their key: a collision locks more, never less.
  std::unordered_map<uint64_t, int> ownerGroup;
  std::unordered_map<uint64_t, bool> shared;
  std::vector<Triangles> groupTris(groups.size());
  for (size_t g = 0; g < groups.size(); ++g)
    for (uint32_t id : groups[g]) {
      const Cluster& c = h.clusters[id];
      for (uint32_t i = 0; i < c.triangleCount * 3; ++i) {
        const uint32_t v = h.indices[c.firstIndex + i];
        groupTris[g].push_back(v);
        const uint64_t key = positionKey(h.positions[v]);
        auto [it, first] = ownerGroup.try_emplace(key, int(g));
        if (!first && it->second != int(g)) shared[key] = true;
      }
    }
  std::vector<uint8_t> locked(h.positions.size(), 0);
  for (size_t v = 0; v < h.positions.size(); ++v)
    locked[v] = shared.count(positionKey(h.positions[v])) || (externalLock && externalLock(h.positions[v])) ? 1 : 0;
  std::vector<GroupResult> results(groups.size());
  parallelFor(int64_t(groups.size()), int(threads), 1, [&](int64_t b, int64_t e) {
    for (int64_t g = b; g < e && !isCancelled(progress); ++g)
      results[size_t(g)] = simplifyGroup(h.positions, h.uvs, groupTris[size_t(g)], locked, options);
  });
  if (isCancelled(progress)) {
    step.cancelled = true;
    return step;
  }
  // Merged in group order: the pool and the clusters come out the same
  // whatever the thread count.
  for (size_t g = 0; g < groups.size(); ++g) {
    GroupResult& r = results[g];
    ++rep.groups;
    if (!r.simplified) {
      ++rep.groupsKept;
      step.next.insert(step.next.end(), groups[g].begin(), groups[g].end());
      continue;
    }
    ++step.simplified;
    LodSphere sphere = sphereOf(h.positions, groupTris[g].data(), groupTris[g].size());
    // The distance to the input adds up along the levels (Hausdorff's
    // triangle inequality): the children's largest plus this group's own.
    float childError = 0.0f;
    for (uint32_t id : groups[g]) {
      sphere = merged(sphere, h.clusters[id].lodBounds);
      childError = std::max(childError, h.clusters[id].error);
    }
    const float error = childError + r.error;  // so also monotonic up the hierarchy
    const uint32_t groupId = h.groups++;
    for (uint32_t id : groups[g]) {
      h.clusters[id].parentBounds = sphere;
      h.clusters[id].parentError = error;
      h.clusters[id].parentGroup = groupId;
    }
    std::vector<uint32_t> toPool(r.positions.size());
    for (size_t i = 0; i < r.positions.size(); ++i) {
      if (r.poolIndex[i] >= 0) {
        toPool[i] = uint32_t(r.poolIndex[i]);
      } else {
        toPool[i] = uint32_t(h.positions.size());
        h.positions.push_back(r.positions[i]);
        if (!h.uvs.empty()) h.uvs.push_back(r.uvs[i]);
      }
    }
    for (Triangles& c : r.clusters) {
      for (uint32_t& v : c) v = toPool[v];
      step.next.push_back(uint32_t(h.clusters.size()));
      step.triangles += c.size() / 3;
      addCluster(h, c, level, sphere, error);
      h.clusters.back().group = groupId;
    }
  }
  return step;
}

ClusterHierarchy buildClusterHierarchy(const MeshData& mesh, const ClusterOptions& options,
                                       ClusterBuildReport* report, const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ClusterBuildReport rep;
  ClusterHierarchy h;
  h.origin = mesh.origin;
  // Weld where position and UV agree: split normals do not cut the
  // surface; a UV seam stays two vertices a side.
  Triangles tris = weldForClusters(mesh.positions, mesh.uvs, mesh.indices, h.positions, h.uvs);
  if (tris.empty()) {
    if (report) *report = rep;
    return h;
  }
  // Level 0: the input in clusters, triangles in spatial order first (the
  // meshlet builder follows the index order).
  Triangles sorted(tris.size());
  meshopt_spatialSortTriangles(sorted.data(), tris.data(), tris.size(), &h.positions[0].x, h.positions.size(),
                               sizeof(glm::vec3));
  std::vector<uint32_t> active;
  for (const Triangles& c : meshletsOf(h.positions, sorted, options)) {
    active.push_back(uint32_t(h.clusters.size()));
    addCluster(h, c, 0, {}, 0.0f);
  }
  rep.clustersPerLevel.push_back(active.size());
  rep.trianglesPerLevel.push_back(tris.size() / 3);
  for (uint32_t level = 1; active.size() > 1 && level < 64; ++level) {
    LevelStep step = simplifyLevel(h, active, level, options, {}, {}, rep, progress);
    if (step.cancelled) return {};
    std::vector<uint32_t>& next = step.next;
    const size_t simplified = step.simplified, levelTriangles = step.triangles;
    if (simplified == 0) break;  // every group held by its border: these are the roots
    h.levels = level;
    active = std::move(next);
    rep.clustersPerLevel.push_back(active.size());
    rep.trianglesPerLevel.push_back(levelTriangles);
    // Each level has about half the triangles of the one before.
    reportProgress(progress, 1.0 - std::ldexp(1.0, -int(level)), "Building the cluster hierarchy");
  }
  ++h.levels;  // counted from 1: level 0 alone is one level
  for (uint32_t id : active) h.clusters[id].parentError = std::numeric_limits<float>::infinity();
  rep.roots = active.size();
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = rep;
  return h;
}

CutSummary summariseCut(const ClusterHierarchy& h, const std::vector<uint32_t>& cut) {
  CutSummary s;
  for (uint32_t id : cut) {
    s.triangles += h.clusters[id].triangleCount;
    s.maxError = std::max(s.maxError, h.clusters[id].error);
  }
  return s;
}

MeshData meshOfCut(const ClusterHierarchy& h, const std::vector<uint32_t>& cut) {
  // Only the vertices the cut uses (an error report samples every vertex).
  MeshData m;
  m.origin = h.origin;
  std::vector<uint32_t> local(h.positions.size(), UINT32_MAX);
  for (uint32_t id : cut) {
    const Cluster& c = h.clusters[id];
    for (uint32_t i = c.firstIndex; i < c.firstIndex + c.triangleCount * 3; ++i) {
      const uint32_t v = h.indices[i];
      if (local[v] == UINT32_MAX) {
        local[v] = uint32_t(m.positions.size());
        m.positions.push_back(h.positions[v]);
        if (!h.uvs.empty()) m.uvs.push_back(h.uvs[v]);
      }
      m.indices.push_back(local[v]);
    }
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

bool lodFineEnough(const LodSphere& sphere, float error, const glm::vec3& eye, float focalPx, float pixelBound) {
  if (error <= 0.0f) return true;
  if (!std::isfinite(error)) return false;
  const float distance = glm::length(eye - sphere.centre) - sphere.radius;
  if (distance <= 0.0f) return false;
  return error * focalPx / distance <= pixelBound;
}

std::vector<uint32_t> selectClusterCut(const ClusterHierarchy& h, const glm::vec3& eye, float focalPx,
                                       float pixelBound) {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < h.clusters.size(); ++i) {
    const Cluster& c = h.clusters[i];
    if (lodFineEnough(c.lodBounds, c.error, eye, focalPx, pixelBound) &&
        !lodFineEnough(c.parentBounds, c.parentError, eye, focalPx, pixelBound))
      out.push_back(i);
  }
  return out;
}

}  // namespace hs::mesh

namespace hs::mesh {

std::vector<uint32_t> uniformClusterCut(const ClusterHierarchy& h, size_t maxTriangles, float* errorOut) {
  return uniformCutOf(h.clusters, maxTriangles, errorOut);
}

}  // namespace hs::mesh
