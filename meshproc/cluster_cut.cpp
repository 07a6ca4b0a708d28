#include "meshproc/cluster_cut.h"

#include <algorithm>
#include <cmath>

#include "meshproc/uniform_cut.h"

namespace hs::mesh {
namespace {

// Compressed rows: for each key in [0, keys), the values whose key it is,
// in the order given.
void buildRows(size_t keys, const std::vector<std::pair<uint32_t, uint32_t>>& pairs, std::vector<uint32_t>& first,
               std::vector<uint32_t>& values) {
  first.assign(keys + 1, 0);
  for (const auto& [k, v] : pairs) ++first[k + 1];
  for (size_t k = 0; k < keys; ++k) first[k + 1] += first[k];
  values.resize(pairs.size());
  std::vector<uint32_t> at(first.begin(), first.end() - 1);
  for (const auto& [k, v] : pairs) values[at[k]++] = v;
}

}  // namespace

ClusterGroups clusterGroupsOf(const ClusterIndex& index) {
  ClusterGroups g;
  std::vector<std::pair<uint32_t, uint32_t>> children, made, pages;
  for (uint32_t i = 0; i < index.clusters.size(); ++i) {
    const ClusterIndexEntry& e = index.clusters[i];
    if (e.parentGroup != kNoGroup) {
      children.emplace_back(e.parentGroup, i);
      pages.emplace_back(e.parentGroup, e.page);
    } else {
      g.roots.push_back(i);
      g.rootPages.push_back(e.page);
    }
    if (e.group != kNoGroup) made.emplace_back(e.group, i);
  }
  buildRows(index.groupCount, children, g.childrenFirst, g.children);
  buildRows(index.groupCount, made, g.madeFirst, g.made);
  // Distinct pages per group (a group's children sit in a few neighbouring pages).
  std::sort(pages.begin(), pages.end());
  pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
  buildRows(index.groupCount, pages, g.childPagesFirst, g.childPages);
  std::sort(g.rootPages.begin(), g.rootPages.end());
  g.rootPages.erase(std::unique(g.rootPages.begin(), g.rootPages.end()), g.rootPages.end());
  return g;
}

ResidentCut selectResidentCut(const ClusterIndex& index, const ClusterGroups& groups, const CutViewer& viewer,
                              const std::function<bool(uint32_t page)>& resident,
                              const std::function<bool(const LodSphere& sphere)>& visible) {
  ResidentCut cut;
  for (uint32_t p : groups.rootPages)
    if (!resident(p)) {
      cut.rootsResident = cut.complete = false;
      cut.wanted.push_back(p);
    }
  if (!cut.rootsResident) return cut;  // the roots come first: asked for, nothing drawn yet

  const uint32_t groupCount = index.groupCount;
  // Which groups the view asks to refine, from the bottom up (a group is
  // made before every group above it: increasing ids go up): its own
  // error over the bound where one of its children is seen, or a group
  // below it asking (whose parents must refine first for it to). Without
  // `visible` this is just "its error is over the bound" (monotonic).
  std::vector<uint8_t> demand(groupCount, 0);
  for (uint32_t g = 0; g < groupCount; ++g) {
    const uint32_t madeBegin = groups.madeFirst[g];
    if (madeBegin == groups.madeFirst[g + 1]) continue;  // (a sound index has none such)
    const ClusterIndexEntry& out = index.clusters[groups.made[madeBegin]];
    if (lodFineEnough(out.lodBounds, out.error, viewer.eye, viewer.focalPx, viewer.pixelBound)) {
      // Fine, unless a group below asks (float rounding of a monotonic test).
    } else if (!visible) {
      demand[g] = 1;
      continue;
    } else {
      // Refined only where a child would be seen: a group whose children
      // all lie outside every view is drawn as it is (and culled there).
      for (uint32_t k = groups.childrenFirst[g]; k < groups.childrenFirst[g + 1] && !demand[g]; ++k)
        demand[g] = visible(index.clusters[groups.children[k]].bounds);
      if (demand[g]) continue;
    }
    for (uint32_t k = groups.childrenFirst[g]; k < groups.childrenFirst[g + 1] && !demand[g]; ++k) {
      const uint32_t below = index.clusters[groups.children[k]].group;
      demand[g] = below != kNoGroup && demand[below];
    }
  }
  std::vector<uint8_t> refined(groupCount, 0);
  std::vector<std::pair<float, uint32_t>> waiting;  // (projected error, page)
  // Then from the roots down (decreasing ids).
  for (uint32_t g = groupCount; g-- > 0;) {
    if (!demand[g]) continue;
    const uint32_t madeBegin = groups.madeFirst[g], madeEnd = groups.madeFirst[g + 1];
    const ClusterIndexEntry& out = index.clusters[groups.made[madeBegin]];
    bool above = true;
    for (uint32_t k = madeBegin; k < madeEnd && above; ++k) {
      const uint32_t pg = index.clusters[groups.made[k]].parentGroup;
      above = pg == kNoGroup || refined[pg];
    }
    if (!above) continue;
    bool all = true;
    for (uint32_t k = groups.childPagesFirst[g]; k < groups.childPagesFirst[g + 1]; ++k)
      if (!resident(groups.childPages[k])) {
        all = false;
        const float d = glm::length(viewer.eye - out.lodBounds.centre) - out.lodBounds.radius;
        const float projected = d > 0.0f ? out.error * viewer.focalPx / d : INFINITY;
        waiting.emplace_back(projected, groups.childPages[k]);
      }
    if (!all) {
      cut.complete = false;
      continue;
    }
    refined[g] = 1;
    ++cut.groupsRefined;
  }
  for (uint32_t i = 0; i < index.clusters.size(); ++i) {
    const ClusterIndexEntry& e = index.clusters[i];
    if ((e.parentGroup == kNoGroup || refined[e.parentGroup]) && (e.group == kNoGroup || !refined[e.group]))
      cut.clusters.push_back(i);
  }
  // Most wanted first, each page once (its largest error), ties by page.
  std::sort(waiting.begin(), waiting.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<uint8_t> listed;
  for (const auto& [e, p] : waiting) {
    if (listed.size() <= p) listed.resize(size_t(p) + 1, 0);
    if (!listed[p]) {
      listed[p] = 1;
      cut.wanted.push_back(p);
    }
  }
  return cut;
}

std::vector<uint32_t> uniformIndexCut(const ClusterIndex& index, size_t maxTriangles, float* error) {
  return uniformCutOf(index.clusters, maxTriangles, error);
}

}  // namespace hs::mesh
