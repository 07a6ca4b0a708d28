#include "meshproc/cluster_cut.h"

#include <algorithm>
#include <cmath>

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
  std::vector<uint8_t> refined(groupCount, 0);
  std::vector<std::pair<float, uint32_t>> waiting;  // (projected error, page)
  // A group is made after every group below it: decreasing ids go down.
  for (uint32_t g = groupCount; g-- > 0;) {
    const uint32_t madeBegin = groups.madeFirst[g], madeEnd = groups.madeFirst[g + 1];
    if (madeBegin == madeEnd) continue;  // (a sound index has none such)
    const ClusterIndexEntry& out = index.clusters[groups.made[madeBegin]];
    if (lodFineEnough(out.lodBounds, out.error, viewer.eye, viewer.focalPx, viewer.pixelBound)) continue;
    bool above = true;
    for (uint32_t k = madeBegin; k < madeEnd && above; ++k) {
      const uint32_t pg = index.clusters[groups.made[k]].parentGroup;
      above = pg == kNoGroup || refined[pg];
    }
    if (!above) continue;
    if (visible && !visible(out.lodBounds)) continue;
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

}  // namespace hs::mesh
