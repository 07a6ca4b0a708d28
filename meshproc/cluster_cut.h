#pragma once
// A view's cut through a paged cluster hierarchy (issue 38 items 3-4;
// cluster_pages.h) when not every page is in memory: the index alone says
// where the view wants more detail, the pages it has say how much it can
// draw now, and what is missing is asked for.
//
// Groups decide, from the roots down: a group is refined (its children
// drawn or refined further instead of the clusters it made) when its own
// test fails (its error projects over the pixel bound), every group above
// it (those its clusters were simplified in) is refined or unseen, one of
// its children's spheres meets a view (`visible`) and every page holding
// one of its children is resident. A group whose children nobody sees is
// not refined (its finer pages are never needed) but counts as refined for
// the groups under it: they share clusters with seen groups, and stopping
// there left the seen part coarse. A cluster is drawn when the group it
// was simplified in is refined (a root: always) and the group that made it
// is not (level 0: never refined). Where everything is seen each piece of
// surface has exactly one level, as with selectClusterCut: a group's
// children and what it made cover the same surface inside the same locked
// border, and a group only refines under refined groups. Beside an unseen
// group the clusters it made are drawn as well as the finer clusters of a
// seen group under it: they overlap there, near the edge of what is seen,
// and never leave a hole (shadow views draw the same cut). With every page
// resident the seen clusters are selectClusterCut's, except a seen cluster
// whose finer clusters are all unseen; with pages missing, the coarser
// level stays where the finer is not in memory (never a hole), and those
// pages are asked for, the largest projected error first.
//
// The walk starts at the groups under the roots and only looks at the
// children of groups it refines, so a cut costs what it draws, not what
// the index holds (a 100M-triangle scan's index has 1.7M clusters; a low
// flight draws a few percent of them). The error test is monotonic up the
// hierarchy (errors grow, spheres nest: clusterIndexProblem checks both),
// so stopping at a group that is fine enough misses nothing below it but
// float ties. Unseen groups are walked through where the error asks for
// more (beside and behind the view), without their pages; the render source
// widens the view it refines through so the overlap stays outside the
// views it draws.
#include <cstdint>
#include <functional>
#include <vector>

#include "meshproc/cluster_pages.h"

namespace hs::mesh {

// Each group's children and the clusters it made, found once per index,
// laid out for the walk: what a group's test reads in one place, each
// child's own group beside it (no trip to the index entries, which are 80
// bytes apart: at 1.7M clusters the walk is bound by memory latency).
struct ClusterGroups {
  struct Test {  // the group's sphere and error (every cluster it made has them)
    LodSphere sphere;
    float error = 0.0f;
  };
  std::vector<Test> tests;                        // per group
  std::vector<uint32_t> childrenFirst, children;  // CSR: clusters simplified in group g
  std::vector<uint32_t> childGroup;               // per entry of `children`: the group that made it (kNoGroup: level 0)
  std::vector<uint32_t> madeFirst, made;          // CSR: clusters group g made
  std::vector<uint32_t> childPagesFirst, childPages;  // CSR: distinct pages of g's children
  std::vector<uint32_t> childGroupsFirst, childGroups;  // CSR: distinct groups that made g's children
  std::vector<uint32_t> parentsNeeded;  // per group: distinct groups its clusters were simplified in
  std::vector<uint32_t> topGroups;      // groups that made only roots (parentsNeeded 0)
  std::vector<uint32_t> roots;          // clusters with no parent group
  std::vector<uint32_t> rootPages;      // their distinct pages
};
ClusterGroups clusterGroupsOf(const ClusterIndex& index);

struct CutViewer {
  glm::vec3 eye{0.0f};  // in the index's local coordinates
  float focalPx = 1.0f;
  float pixelBound = 1.0f;
};

struct ResidentCut {
  std::vector<uint32_t> clusters;  // drawn, in index order
  // Pages the cut wants that are not resident, most wanted first (the
  // largest projected error of a group waiting for them), each once.
  std::vector<uint32_t> wanted;
  bool rootsResident = true;  // false: some root's page is missing (nothing of the hierarchy can be drawn whole)
  bool complete = true;       // no group held coarse for want of a page
  size_t groupsRefined = 0;
  size_t groupsTested = 0;  // groups whose test ran: the cut's cost (those next to it, not the index's)
};

// `resident(page)`: whether the page is in memory; `visible(sphere)`:
// whether a cluster's sphere meets a view that draws the cut (null: all).
ResidentCut selectResidentCut(const ClusterIndex& index, const ClusterGroups& groups, const CutViewer& viewer,
                              const std::function<bool(uint32_t page)>& resident,
                              const std::function<bool(const LodSphere& sphere)>& visible = {});

// The cut one bound of `error` metres takes everywhere, from the index
// alone (as uniformClusterCut on a built hierarchy): the smallest error
// whose cut has at most `maxTriangles`.
std::vector<uint32_t> uniformIndexCut(const ClusterIndex& index, size_t maxTriangles, float* error = nullptr);

}  // namespace hs::mesh
