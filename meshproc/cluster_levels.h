#pragma once
// The two steps a cluster hierarchy is built from, shared by the in-core
// builder (cluster_hierarchy.cpp: the whole scan at once) and the streamed
// one (cluster_build_streamed.h: cell by cell of a spatial partition, each
// cell's border locked until its neighbours join it): add a cluster, and
// take one level (group the active clusters, simplify each group to half
// with its border locked, cut the results into clusters).
#include <cstdint>
#include <functional>
#include <vector>

#include "meshproc/cluster_hierarchy.h"

namespace hs::mesh {

// Appends a cluster of `tris` (pool indices) at `level`, made with `error`
// in a group of sphere `lodBounds` (level 0: its own bounds, error 0).
void addCluster(ClusterHierarchy& h, const std::vector<uint32_t>& tris, uint32_t level, const LodSphere& lodBounds,
                float error);

// Whether a vertex at this position is shared with triangles outside the
// hierarchy being built (locked at every level); empty: none is.
using ExternalLock = std::function<bool(const glm::vec3& position)>;
// Called with the level's groups (cluster ids) before they are simplified.
using GroupedHook = std::function<void(const std::vector<std::vector<uint32_t>>& groups)>;

struct LevelStep {
  std::vector<uint32_t> next;  // the clusters of the next level: those made, and those of groups kept
  size_t simplified = 0;       // groups that made clusters (0: `active` are roots, or held by a locked border)
  size_t triangles = 0;        // in the clusters made
  bool cancelled = false;
};

// Groups `active` (neighbours by shared edges, in Morton order), simplifies
// each group to half with the borders between groups (and the external
// ones) locked, in parallel, and merges the results in group order (the
// same for any thread count): new clusters at `level` get the group's
// error and sphere, their children the parent test; group ids continue
// from h.groups. Counts groups into `rep`.
LevelStep simplifyLevel(ClusterHierarchy& h, const std::vector<uint32_t>& active, uint32_t level,
                        const ClusterOptions& options, const ExternalLock& externalLock, const GroupedHook& onGrouped,
                        ClusterBuildReport& rep, const Progress* progress);

}  // namespace hs::mesh
