#include "meshproc/cluster_from_tiles.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <limits>

#include "meshproc/cluster_parts.h"

namespace hs::mesh {
namespace {

struct TileClusters {
  std::vector<uint32_t> own;      // the tile's content as clusters (what its group made, or level 0)
  std::vector<uint32_t> addCopy;  // an ADD tile's content again, level 0 under its own group
  uint32_t group = kNoGroup;      // its group when it has children
  uint32_t height = 0;            // 0 for a leaf
  float error = 0.0f;             // its clusters' error (0 for a leaf)
};

// The tile's triangles as clusters appended to `h`, level 0 for now.
std::vector<uint32_t> clustersOf(ClusterHierarchy& h, const LodTile& t, bool uvs, const ClusterOptions& o) {
  std::vector<glm::vec2> noUvs;
  std::vector<uint32_t> tris = weldForClusters(t.positions, uvs ? t.uvs : noUvs, t.indices, h.positions, h.uvs);
  if (tris.empty()) return {};
  std::vector<uint32_t> sorted(tris.size());
  meshopt_spatialSortTriangles(sorted.data(), tris.data(), tris.size(), &h.positions[0].x, h.positions.size(),
                               sizeof(glm::vec3));
  std::vector<uint32_t> ids;
  for (const std::vector<uint32_t>& c : meshletsOf(h.positions, sorted, o)) {
    Cluster cl;
    cl.firstIndex = uint32_t(h.indices.size());
    cl.triangleCount = uint32_t(c.size() / 3);
    h.indices.insert(h.indices.end(), c.begin(), c.end());
    cl.bounds = sphereOf(h.positions, c.data(), c.size());
    cl.lodBounds = cl.bounds;
    ids.push_back(uint32_t(h.clusters.size()));
    h.clusters.push_back(cl);
  }
  return ids;
}

// Whether any triangle has three distinct positions (one that welding
// keeps, so the tile makes at least one cluster).
bool hasTriangles(const LodTile& t) {
  for (size_t i = 0; i + 2 < t.indices.size(); i += 3) {
    const glm::vec3 &a = t.positions[t.indices[i]], &b = t.positions[t.indices[i + 1]], &c = t.positions[t.indices[i + 2]];
    if (a != b && b != c && a != c) return true;
  }
  return false;
}

}  // namespace

ClusterHierarchy clusterHierarchyOfTiles(const std::vector<LodTile>& tiles, const glm::dvec3& origin,
                                         const ClusterOptions& options, TileHierarchyReport* report) {
  TileHierarchyReport rep;
  ClusterHierarchy h;
  h.origin = origin;
  const size_t n = tiles.size();
  // Tiles with content, each hung under its nearest ancestor with content.
  std::vector<uint8_t> content(n, 0);
  for (size_t i = 0; i < n; ++i) content[i] = hasTriangles(tiles[i]) ? 1 : 0;
  auto contentAbove = [&](size_t i) {
    int p = tiles[i].parent;
    while (p >= 0 && !content[size_t(p)]) p = tiles[size_t(p)].parent;
    return p;
  };
  // A missing content with nothing below to stand in: its nearest ancestor
  // with content stays whole (refining it would open a hole).
  std::vector<uint8_t> below(n, 0), whole(n, 0), out(n, 0);
  for (size_t i = n; i-- > 0;)
    if (tiles[i].parent >= 0 && (content[i] || below[i])) below[size_t(tiles[i].parent)] = 1;
  for (size_t i = 0; i < n; ++i) {
    if (!tiles[i].missing || content[i] || below[i]) continue;
    const int p = contentAbove(i);
    if (p < 0 || whole[size_t(p)]) continue;
    whole[size_t(p)] = 1;
    rep.warnings.push_back((tiles[size_t(p)].name.empty() ? "a tile" : tiles[size_t(p)].name) +
                           ": kept at its own level everywhere (its children are left out): " +
                           (tiles[i].name.empty() ? "a child tile" : "child " + tiles[i].name) +
                           "'s content did not come in");
  }
  for (size_t i = 0; i < n; ++i) {
    const int p = tiles[i].parent;
    out[i] = p >= 0 && (out[size_t(p)] || whole[size_t(p)]);
    if (out[i]) {
      rep.tilesLeftOut += content[i];
      content[i] = 0;
    }
  }
  bool uvs = true;
  for (size_t i = 0; i < n; ++i) {
    if (content[i]) {
      ++rep.tilesWithContent;
      uvs = uvs && tiles[i].uvs.size() == tiles[i].positions.size();
    } else if (!out[i]) {
      ++rep.tilesPassedThrough;
    }
  }
  std::vector<std::vector<uint32_t>> kids(n);
  for (size_t i = 0; i < n; ++i) {
    if (!content[i]) continue;
    const int p = contentAbove(i);
    if (p >= 0) kids[size_t(p)].push_back(uint32_t(i));
  }
  // Children before parents (parents come first in the list): group ids
  // then grow up the tree, as the cut walks them.
  std::vector<TileClusters> made(n);
  for (size_t k = n; k-- > 0;) {
    if (!content[k]) continue;
    const LodTile& t = tiles[k];
    TileClusters& m = made[k];
    m.own = clustersOf(h, t, uvs, options);
    if (kids[k].empty()) continue;  // a leaf: level 0, error 0
    // Its group: the error and sphere of drawing it instead of everything below.
    float worstBelow = 0.0f;
    uint32_t height = 0;
    for (uint32_t c : kids[k]) worstBelow = std::max(worstBelow, made[c].error), height = std::max(height, made[c].height);
    m.height = height + 1;
    m.error = std::max(t.error, worstBelow);
    if (t.error < worstBelow) {
      ++rep.errorsRaised;
      if (rep.errorsRaised <= 8)
        rep.warnings.push_back((t.name.empty() ? "a tile" : t.name) + ": its geometric error " + std::to_string(t.error) +
                               " m is below its children's " + std::to_string(worstBelow) + " m; raised to it");
    }
    if (t.additive) {
      m.addCopy = clustersOf(h, t, uvs, options);
      ++rep.additiveCopies;
      for (uint32_t id : m.addCopy) rep.additiveCopyTriangles += h.clusters[id].triangleCount;
    }
    m.group = h.groups++;
    LodSphere sphere = h.clusters[m.own.front()].bounds;
    for (uint32_t id : m.own) sphere = merged(sphere, h.clusters[id].bounds);
    std::vector<uint32_t> children = m.addCopy;
    for (uint32_t c : kids[k]) children.insert(children.end(), made[c].own.begin(), made[c].own.end());
    for (uint32_t id : children) sphere = merged(sphere, h.clusters[id].lodBounds);
    for (uint32_t id : m.own) {
      Cluster& c = h.clusters[id];
      c.level = m.height;
      c.group = m.group;
      c.lodBounds = sphere;
      c.error = m.error;
    }
    for (uint32_t id : children) {
      Cluster& c = h.clusters[id];
      c.parentGroup = m.group;
      c.parentError = m.error;
      c.parentBounds = sphere;
    }
  }
  uint32_t top = 0;
  for (size_t k = 0; k < n; ++k) top = std::max(top, made[k].height);
  h.levels = h.clusters.empty() ? 0 : top + 1;
  if (rep.errorsRaised > 8)
    rep.warnings.push_back(std::to_string(rep.errorsRaised - 8) + " more tiles had an error below their children's");
  if (report) *report = std::move(rep);
  return h;
}

}  // namespace hs::mesh
