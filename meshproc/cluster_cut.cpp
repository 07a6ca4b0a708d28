#include "meshproc/cluster_cut.h"

#include <algorithm>
#include <bit>
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

// Sorts and drops repeated pairs, so each key's row lists each value once.
void distinct(std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

}  // namespace

ClusterGroups clusterGroupsOf(const ClusterIndex& index) {
  ClusterGroups g;
  std::vector<std::pair<uint32_t, uint32_t>> children, made, pages, childGroups;
  for (uint32_t i = 0; i < index.clusters.size(); ++i) {
    const ClusterIndexEntry& e = index.clusters[i];
    if (e.parentGroup != kNoGroup) {
      children.emplace_back(e.parentGroup, i);
      pages.emplace_back(e.parentGroup, e.page);
      if (e.group != kNoGroup) childGroups.emplace_back(e.parentGroup, e.group);
    } else {
      g.roots.push_back(i);
      g.rootPages.push_back(e.page);
    }
    if (e.group != kNoGroup) made.emplace_back(e.group, i);
  }
  buildRows(index.groupCount, children, g.childrenFirst, g.children);
  buildRows(index.groupCount, made, g.madeFirst, g.made);
  g.childGroup.resize(g.children.size());
  for (size_t k = 0; k < g.children.size(); ++k) g.childGroup[k] = index.clusters[g.children[k]].group;
  g.tests.resize(index.groupCount);
  for (uint32_t k = 0; k < index.groupCount; ++k)
    if (g.madeFirst[k] != g.madeFirst[k + 1]) {
      const ClusterIndexEntry& e = index.clusters[g.made[g.madeFirst[k]]];
      g.tests[k] = {e.lodBounds, e.error};
    }
  // Distinct pages per group (a group's children sit in a few neighbouring pages).
  distinct(pages);
  buildRows(index.groupCount, pages, g.childPagesFirst, g.childPages);
  // A group under pg for each distinct (pg, group) pair: pg is one of the
  // groups its clusters were simplified in.
  distinct(childGroups);
  buildRows(index.groupCount, childGroups, g.childGroupsFirst, g.childGroups);
  g.parentsNeeded.assign(index.groupCount, 0);
  for (const auto& [pg, below] : childGroups) ++g.parentsNeeded[below];
  for (uint32_t k = 0; k < index.groupCount; ++k)
    if (g.parentsNeeded[k] == 0 && g.madeFirst[k] != g.madeFirst[k + 1]) g.topGroups.push_back(k);
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

  // A group is looked at once every group above it is refined or unseen
  // (`above` counts them in), so only groups next to the cut are ever
  // touched.
  const uint32_t groupCount = index.groupCount;
  std::vector<uint32_t> above(groupCount, 0);
  std::vector<uint8_t> refined(groupCount, 0);
  std::vector<uint32_t> ready(groups.topGroups.begin(), groups.topGroups.end());
  std::vector<uint32_t> refinedList;
  std::vector<std::pair<float, uint32_t>> waiting;  // (projected error, page)
  auto passDown = [&](uint32_t g) {
    for (uint32_t k = groups.childGroupsFirst[g]; k < groups.childGroupsFirst[g + 1]; ++k) {
      const uint32_t below = groups.childGroups[k];
      if (++above[below] == groups.parentsNeeded[below]) ready.push_back(below);
    }
  };
  while (!ready.empty()) {
    const uint32_t g = ready.back();
    ready.pop_back();
    ++cut.groupsTested;
    const ClusterGroups::Test& test = groups.tests[g];
    // Fine enough: so is every group under it (errors grow upwards, spheres
    // nest), which stays unrefined whether it is looked at or not.
    if (lodFineEnough(test.sphere, test.error, viewer.eye, viewer.focalPx, viewer.pixelBound)) continue;
    if (visible) {
      // Refined only where a child would be seen: a group whose children
      // all lie outside every view is drawn as it is (and culled there).
      // The groups under it still count it as refined: they share clusters
      // with seen groups, and would otherwise never be looked at, leaving
      // the seen part coarse. Where one of them is refined, its finer
      // clusters are drawn beside the clusters this group made (it is not
      // refined): they overlap only near the edge of what is seen.
      bool seen = false;
      for (uint32_t k = groups.childrenFirst[g]; k < groups.childrenFirst[g + 1] && !seen; ++k)
        seen = visible(index.clusters[groups.children[k]].bounds);
      if (!seen) {
        passDown(g);
        continue;
      }
    }
    bool all = true;
    for (uint32_t k = groups.childPagesFirst[g]; k < groups.childPagesFirst[g + 1]; ++k)
      if (!resident(groups.childPages[k])) {
        all = false;
        const float d = glm::length(viewer.eye - test.sphere.centre) - test.sphere.radius;
        const float projected = d > 0.0f ? test.error * viewer.focalPx / d : INFINITY;
        waiting.emplace_back(projected, groups.childPages[k]);
      }
    if (!all) {
      cut.complete = false;
      continue;
    }
    refined[g] = 1;
    refinedList.push_back(g);
    passDown(g);
  }
  cut.groupsRefined = refinedList.size();
  // Drawn: the roots and the children of refined groups, where the group
  // that made them is not refined (each cluster has one parent group, so
  // none is listed twice), put in index order through a bit per cluster
  // (a sort of the tens of thousands drawn costs more).
  std::vector<uint64_t> drawn((index.clusters.size() + 63) / 64, 0);
  auto draw = [&](uint32_t c, uint32_t made) {
    if (made == kNoGroup || !refined[made]) drawn[c >> 6] |= uint64_t(1) << (c & 63);
  };
  for (uint32_t c : groups.roots) draw(c, index.clusters[c].group);
  for (uint32_t g : refinedList)
    for (uint32_t k = groups.childrenFirst[g]; k < groups.childrenFirst[g + 1]; ++k)
      draw(groups.children[k], groups.childGroup[k]);
  for (size_t w = 0; w < drawn.size(); ++w)
    for (uint64_t bits = drawn[w]; bits; bits &= bits - 1)
      cut.clusters.push_back(uint32_t(w * 64 + size_t(std::countr_zero(bits))));
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
