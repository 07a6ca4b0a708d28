// The cluster hierarchy (meshproc/cluster_hierarchy.h) on a bumpy closed
// sphere: clusters within their size, every level smaller than the one
// below, errors and spheres monotonic up the hierarchy; any cut is
// watertight (every edge of its triangles shared by exactly two, as on the
// closed input), whatever the viewer's place and pixel bound, with levels
// mixed where the viewer is near one side; the finest bound draws the
// input, the coarsest the roots; the same hierarchy for any thread count;
// an open grid with a UV seam keeps its seam (two vertices a side, with
// their UVs) and every cut of it whole at the positions' level, open only
// along the grid's border;
// the surface of a coarse cut stays within its clusters' largest error of
// the input (measured by sampling, meshproc/error_metrics.h); an empty mesh
// gives none. Its pages (meshproc/cluster_pages.h) give every cluster
// back; a truncated or damaged index or page, or errors that shrink up the
// hierarchy, are refused with a message naming the page or cluster.
#include <QtTest>

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "mesh_builders.h"
#include "meshproc/closest_point_bvh.h"
#include "meshproc/cluster_cut.h"
#include "meshproc/cluster_hierarchy.h"
#include "meshproc/cluster_pages.h"
#include "meshproc/error_metrics.h"

using namespace hs;
using mesh::ClusterHierarchy;

namespace {

// Edge -> how many of the cut's triangles use it.
std::map<std::pair<uint32_t, uint32_t>, int> edgeUse(const ClusterHierarchy& h, const std::vector<uint32_t>& cut) {
  std::map<std::pair<uint32_t, uint32_t>, int> use;
  for (uint32_t id : cut) {
    const mesh::Cluster& c = h.clusters[id];
    for (uint32_t t = 0; t < c.triangleCount; ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t u = h.indices[c.firstIndex + t * 3 + k], v = h.indices[c.firstIndex + t * 3 + (k + 1) % 3];
        ++use[std::minmax(u, v)];
      }
  }
  return use;
}


// Index ids (paginate's order) as the hierarchy's cluster ids, sorted.
std::vector<uint32_t> inHierarchy(const mesh::ClusterPages& pages, const std::vector<uint32_t>& ids) {
  std::vector<uint32_t> out;
  for (uint32_t id : ids) out.push_back(pages.order[id]);
  std::sort(out.begin(), out.end());
  return out;
}

// Input vertices the cut leaves uncovered: further from the cut's triangles
// than the largest error of the drawn clusters that could stand for them
// (those whose bounds, widened by their error, hold the vertex). A hole
// leaves the vertices inside it uncovered; overlapping clusters do not.
size_t uncoveredVertices(const ClusterHierarchy& h, const mesh::MeshData& input, const std::vector<uint32_t>& cut) {
  mesh::MeshData drawn;
  drawn.positions = h.positions;
  for (uint32_t id : cut) {
    const mesh::Cluster& c = h.clusters[id];
    drawn.indices.insert(drawn.indices.end(), h.indices.begin() + c.firstIndex,
                         h.indices.begin() + c.firstIndex + c.triangleCount * 3);
  }
  drawn.submeshes.push_back({0, uint32_t(drawn.indices.size()), -1});
  const mesh::ClosestPointBvh bvh(drawn, 1);
  size_t uncovered = 0;
  for (const glm::vec3& p : input.positions) {
    float allowed = 0.0f;
    for (uint32_t id : cut) {
      const mesh::Cluster& c = h.clusters[id];
      if (glm::length(p - c.bounds.centre) <= c.bounds.radius + c.error + 1e-4f) allowed = std::max(allowed, c.error);
    }
    if (std::sqrt(bvh.closest(glm::dvec3(p)).distanceSq) > double(allowed) + 1e-4) ++uncovered;
  }
  return uncovered;
}

bool inside(const mesh::LodSphere& a, const mesh::LodSphere& b) {
  return glm::length(a.centre - b.centre) + a.radius <= b.radius * (1.0f + 1e-5f) + 1e-5f;
}

}  // namespace

class TestMeshprocClusters : public QObject {
  Q_OBJECT
  mesh::MeshData sphere_;
  ClusterHierarchy h_;
  mesh::ClusterBuildReport report_;

 private slots:
  void initTestCase() {
    sphere_ = test::bumpySphere();
    h_ = mesh::buildClusterHierarchy(sphere_, {}, &report_);
    QString levels;
    for (size_t l = 0; l < report_.trianglesPerLevel.size(); ++l)
      levels += QString(" %1/%2").arg(report_.clustersPerLevel[l]).arg(report_.trianglesPerLevel[l]);
    qInfo("%zu triangles: %u levels (clusters/triangles:%s), %zu groups (%zu kept as they were), %zu roots, %.2f s",
          sphere_.triangleCount(), h_.levels, qPrintable(levels), report_.groups, report_.groupsKept, report_.roots,
          report_.seconds);
  }

  void levelsShrinkAndErrorsGrow() {
    QVERIFY(h_.levels >= 4);
    QVERIFY(report_.roots <= 4);
    for (size_t l = 1; l < report_.trianglesPerLevel.size(); ++l)
      QVERIFY(report_.trianglesPerLevel[l] < report_.trianglesPerLevel[l - 1]);
    for (const mesh::Cluster& c : h_.clusters) {
      QVERIFY(c.triangleCount >= 1 && c.triangleCount <= 128);
      QVERIFY(c.parentError >= c.error);
      if (std::isfinite(c.parentError)) QVERIFY(inside(c.lodBounds, c.parentBounds));
      QVERIFY(c.level == 0 ? c.error == 0.0f : c.error > 0.0f);
    }
  }

  void everyCutIsWatertight() {
    const float focal = 1000.0f;
    bool mixed = false;
    size_t cuts = 0;
    for (const glm::vec3 eye : {glm::vec3(0, -12, 0), glm::vec3(0, -15, 3), glm::vec3(30, 0, 0),
                                glm::vec3(0, 0, 200), glm::vec3(5000, 0, 0)})
      for (float bound : {0.25f, 1.0f, 4.0f, 32.0f}) {
        const std::vector<uint32_t> cut = mesh::selectClusterCut(h_, eye, focal, bound);
        QVERIFY(!cut.empty());
        std::set<uint32_t> levels;
        for (uint32_t id : cut) levels.insert(h_.clusters[id].level);
        mixed |= levels.size() > 1;
        for (const auto& [edge, n] : edgeUse(h_, cut))
          if (n != 2)
            QFAIL(qPrintable(QString("eye (%1, %2, %3), bound %4 px: edge %5-%6 used by %7 triangles")
                                 .arg(eye.x).arg(eye.y).arg(eye.z).arg(bound).arg(edge.first).arg(edge.second).arg(n)));
        ++cuts;
      }
    QVERIFY(mixed);  // a viewer near one side sees fine clusters there and coarse ones beyond
    qInfo("%zu cuts, each watertight", cuts);
  }

  void finestAndCoarsest() {
    std::vector<uint32_t> finest = mesh::selectClusterCut(h_, {0, 0, 20}, 1e9f, 1e-6f);
    size_t triangles = 0;
    for (uint32_t id : finest) {
      QCOMPARE(h_.clusters[id].level, 0u);
      triangles += h_.clusters[id].triangleCount;
    }
    QCOMPARE(triangles, sphere_.triangleCount());
    const std::vector<uint32_t> coarsest = mesh::selectClusterCut(h_, {1e7f, 0, 0}, 1.0f, 1e9f);
    QCOMPARE(coarsest.size(), report_.roots);
    for (uint32_t id : coarsest) QVERIFY(std::isinf(h_.clusters[id].parentError));
  }

  void theSameForAnyThreadCount() {
    mesh::ClusterOptions one;
    one.threads = 1;
    mesh::ClusterOptions two;
    two.threads = 2;
    const ClusterHierarchy a = mesh::buildClusterHierarchy(sphere_, one), b = mesh::buildClusterHierarchy(sphere_, two);
    QVERIFY(a.positions == b.positions);
    QVERIFY(a.indices == b.indices);
    QCOMPARE(a.clusters.size(), b.clusters.size());
    for (size_t i = 0; i < a.clusters.size(); ++i) {
      QCOMPARE(a.clusters[i].error, b.clusters[i].error);
      QCOMPARE(a.clusters[i].parentError, b.clusters[i].parentError);
    }
  }

  void aCoarseCutStaysNearTheSurface() {
    // A distant viewer at 2 px: the cut's largest cluster error against
    // the distance of its surface from the input, both ways.
    const std::vector<uint32_t> cut = mesh::selectClusterCut(h_, {0, -400, 0}, 1000.0f, 2.0f);
    const auto [triangles, worst] = mesh::summariseCut(h_, cut);
    const mesh::ErrorReport e = mesh::measureError(sphere_, mesh::meshOfCut(h_, cut));
    qInfo("a cut of %zu triangles (of %zu): clusters' error at most %.4f m, measured distance %.4f m (max of both "
          "ways)",
          triangles, sphere_.triangleCount(), double(worst), e.hausdorff);
    QVERIFY(triangles < sphere_.triangleCount() / 4);
    QVERIFY(e.hausdorff <= double(worst));  // the errors bound the distance (by their construction)
  }

  void seamsAndBordersHold() {
    // An open grid with a UV seam across it: the seam's vertices stay two
    // a side with their UVs; at the positions' level every cut is whole
    // (each edge inside used by two triangles, the seam included) and its
    // open edges run between the grid's own border vertices.
    const mesh::MeshData grid = test::curvedGrid(48, 10.0, 1.5, true);
    mesh::ClusterBuildReport rep;
    const ClusterHierarchy h = mesh::buildClusterHierarchy(grid, {}, &rep);
    QVERIFY(rep.trianglesPerLevel.size() >= 4);
    QCOMPARE(h.uvs.size(), h.positions.size());
    std::set<std::tuple<float, float, float>> border;
    {
      std::map<std::pair<std::tuple<float, float, float>, std::tuple<float, float, float>>, int> use;
      auto key = [&](uint32_t v) { const glm::vec3& p = grid.positions[v]; return std::make_tuple(p.x, p.y, p.z); };
      for (size_t t = 0; t < grid.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) ++use[std::minmax(key(grid.indices[t + k]), key(grid.indices[t + (k + 1) % 3]))];
      for (const auto& [edge, n] : use)
        if (n == 1) border.insert({edge.first, edge.second});
    }
    size_t seamCopies = 0;  // welded positions with two UVs
    {
      std::map<std::tuple<float, float, float>, int> copies;
      for (const glm::vec3& p : h.positions) ++copies[{p.x, p.y, p.z}];
      for (const auto& [p, n] : copies) seamCopies += n > 1;
    }
    QVERIFY(seamCopies >= 48);  // the seam's vertices, a copy a side
    for (const glm::vec3 eye : {glm::vec3(1, 1, 2), glm::vec3(5, 5, 30), glm::vec3(-40, 5, 10)})
      for (float bound : {0.5f, 2.0f, 16.0f}) {
        const std::vector<uint32_t> cut = mesh::selectClusterCut(h, eye, 1000.0f, bound);
        std::map<std::pair<std::tuple<float, float, float>, std::tuple<float, float, float>>, int> use;
        auto key = [&](uint32_t v) { const glm::vec3& p = h.positions[v]; return std::make_tuple(p.x, p.y, p.z); };
        for (uint32_t id : cut) {
          const mesh::Cluster& c = h.clusters[id];
          for (uint32_t i = 0; i < c.triangleCount * 3; i += 3)
            for (int k = 0; k < 3; ++k)
              ++use[std::minmax(key(h.indices[c.firstIndex + i + k]), key(h.indices[c.firstIndex + i + (k + 1) % 3]))];
        }
        for (const auto& [edge, n] : use) {
          QVERIFY2(n <= 2, "an edge of three triangles");
          if (n == 1)
            QVERIFY2(border.count(edge.first) && border.count(edge.second),
                     qPrintable(QString("eye (%1, %2, %3), %4 px: an open edge inside the grid")
                                    .arg(eye.x).arg(eye.y).arg(eye.z).arg(bound)));
        }
      }
  }

  void tinyAndFarMeshes() {
    // One triangle: one cluster, a root at level 0.
    mesh::MeshData one;
    one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    one.indices = {0, 1, 2};
    one.submeshes.push_back({0, 3, -1});
    ClusterHierarchy h = mesh::buildClusterHierarchy(one);
    QCOMPARE(h.clusters.size(), size_t(1));
    QCOMPARE(h.levels, 1u);
    QCOMPARE(mesh::selectClusterCut(h, {0, 0, 5}, 1000.0f, 1.0f), std::vector<uint32_t>{0});
    // A triangle welded to a sliver of none (two corners at one point) is dropped.
    one.positions.push_back({0, 0, 0});
    one.indices.insert(one.indices.end(), {3, 0, 1});
    one.submeshes[0].indexCount = 6;
    QCOMPARE(mesh::buildClusterHierarchy(one).indices.size(), size_t(3));
    // A scan in UTM coordinates: positions stay local (the origin holds the
    // 4 400 km), the hierarchy as at the origin.
    mesh::MeshData far = sphere_;
    far.origin = {500000.0, 4400000.0, 300.0};
    const ClusterHierarchy f = mesh::buildClusterHierarchy(far);
    QCOMPARE(f.origin, far.origin);
    QVERIFY(f.indices == h_.indices && f.positions == h_.positions);
  }

  // Positions far from the mesh's own origin (a 10 km scan's corner is 5 km
  // out): small clusters' spheres there must still sit inside their
  // parents' after float rounding (the streamed build's self-check found
  // a 1 m cluster 2 km out outside; merged() pads by the coordinates'
  // rounding since), and the index reads back as sound.
  void farFromTheOrigin() {
    mesh::MeshData off = sphere_;
    for (glm::vec3& p : off.positions) p += glm::vec3(4100.0f, -3700.0f, 650.0f);
    const ClusterHierarchy f = mesh::buildClusterHierarchy(off);
    mesh::ClusterPages pages = mesh::paginate(f);
    const std::string problem = mesh::clusterIndexProblem(pages.index);
    QVERIFY2(problem.empty(), problem.c_str());
    for (const mesh::Cluster& c : f.clusters) {
      if (!std::isfinite(c.parentError)) continue;
      QVERIFY(glm::length(glm::dvec3(c.lodBounds.centre) - glm::dvec3(c.parentBounds.centre)) +
                  double(c.lodBounds.radius) <=
              double(c.parentBounds.radius));
    }
  }

  void pagesRoundTrip() {
    // The hierarchy through its index and pages and back: every cluster's
    // triangles at the same positions, pages near their size.
    const mesh::ClusterPages pages = mesh::paginate(h_, 16 << 10);
    QVERIFY(pages.pages.size() > 4);
    const std::vector<uint8_t> indexBytes = mesh::encodeClusterIndex(pages.index);
    std::string error;
    const std::optional<mesh::ClusterIndex> index =
        mesh::decodeClusterIndex(indexBytes.data(), indexBytes.size(), "sphere", error);
    QVERIFY2(index, error.c_str());
    QCOMPARE(index->clusters.size(), h_.clusters.size());
    size_t clusters = 0;
    for (uint32_t p = 0; p < pages.pages.size(); ++p) {
      const std::vector<uint8_t>& bytes = pages.pages[p];
      QVERIFY(bytes.size() <= (16u << 10) + 128 * 12 + 128 * 3 + 8);
      const auto decoded = mesh::decodeClusterPage(bytes.data(), bytes.size(), *index, p, "sphere", error);
      QVERIFY2(decoded, error.c_str());
      for (const mesh::PageCluster& c : *decoded) {
        const mesh::Cluster& o = h_.clusters[pages.order[c.cluster]];
        QCOMPARE(c.triangles.size(), size_t(o.triangleCount) * 3);
        for (size_t i = 0; i < c.triangles.size(); ++i)
          QCOMPARE(c.positions[c.triangles[i]], h_.positions[h_.indices[o.firstIndex + i]]);
        QCOMPARE(index->clusters[c.cluster].error, o.error);
        ++clusters;
      }
    }
    QCOMPARE(clusters, h_.clusters.size());
  }

  void damagedPagesAndIndexesAreRefusedByName() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 16 << 10);
    const std::vector<uint8_t> indexBytes = mesh::encodeClusterIndex(pages.index);
    std::string error;
    // Truncated anywhere: refused, never read past the end.
    for (size_t cut = 0; cut < indexBytes.size(); cut += 97)
      QVERIFY(!mesh::decodeClusterIndex(indexBytes.data(), cut, "scan.hscene: clusters of asset 3", error));
    QVERIFY2(error.find("scan.hscene: clusters of asset 3: truncated") != std::string::npos, error.c_str());
    const std::vector<uint8_t>& page = pages.pages[1];
    for (size_t cut = 0; cut < page.size(); cut += 31)
      QVERIFY(!mesh::decodeClusterPage(page.data(), cut, pages.index, 1, "scan.hscene", error));
    QVERIFY2(error.find("scan.hscene, page 1") != std::string::npos, error.c_str());
    // Errors that shrink up the hierarchy.
    mesh::ClusterIndex bad = pages.index;
    bad.clusters[5].error = bad.clusters[5].parentError * 2.0f + 1.0f;
    QVERIFY(mesh::clusterIndexProblem(bad).find("cluster 5 (level 0): its error") != std::string::npos);
    QVERIFY(mesh::clusterIndexProblem(bad).find("larger than its parent's") != std::string::npos);
    const std::vector<uint8_t> badBytes = mesh::encodeClusterIndex(bad);
    QVERIFY(!mesh::decodeClusterIndex(badBytes.data(), badBytes.size(), "scan.hscene", error));
    QVERIFY(error.find("errors must grow up the hierarchy") != std::string::npos);
    // A NaN position, a corner past its vertices, the wrong page.
    std::vector<uint8_t> nan = page;
    const float q = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(nan.data() + 12 + 8, &q, 4);  // the first cluster's first x
    QVERIFY(!mesh::decodeClusterPage(nan.data(), nan.size(), pages.index, 1, "scan.hscene", error));
    QVERIFY2(error.find("vertex 0: a position that is not finite") != std::string::npos, error.c_str());
    std::vector<uint8_t> corner = page;
    corner.back() = 255;
    QVERIFY(!mesh::decodeClusterPage(corner.data(), corner.size(), pages.index, 1, "scan.hscene", error));
    QVERIFY2(error.find("past its") != std::string::npos, error.c_str());
    QVERIFY(!mesh::decodeClusterPage(page.data(), page.size(), pages.index, 2, "scan.hscene", error));
    QVERIFY2(error.find("which the index places elsewhere") != std::string::npos, error.c_str());
  }

  // With every page in memory the resident cut is selectClusterCut's.
  void residentCutIsTheCutWhenAllIsResident() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 16 << 10);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(pages.index);
    size_t compared = 0;
    for (const glm::vec3 eye : {glm::vec3(0, -12, 0), glm::vec3(0, -15, 3), glm::vec3(30, 0, 0), glm::vec3(5000, 0, 0)})
      for (float bound : {0.25f, 1.0f, 8.0f}) {
        const mesh::ResidentCut cut =
            mesh::selectResidentCut(pages.index, groups, {eye, 1000.0f, bound}, [](uint32_t) { return true; });
        QVERIFY(cut.complete && cut.rootsResident && cut.wanted.empty());
        QVERIFY(inHierarchy(pages, cut.clusters) == mesh::selectClusterCut(h_, eye, 1000.0f, bound));
        ++compared;
      }
    qInfo("%zu cuts equal to selectClusterCut's", compared);
  }

  // Pages missing at random: the cut stays watertight with only resident
  // clusters, asks for pages, and loading what it asks for converges on the
  // full cut; without the roots' pages nothing is drawn and they are asked for.
  void residentCutNeverHasAHole() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 8 << 10);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(pages.index);
    const mesh::CutViewer viewer{glm::vec3(0, -12, 2), 1000.0f, 0.5f};
    const std::vector<uint32_t> ideal = mesh::selectClusterCut(h_, viewer.eye, viewer.focalPx, viewer.pixelBound);
    std::mt19937 rng(7);
    size_t incomplete = 0;
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<uint8_t> resident(pages.index.pageCount);
      for (auto& r : resident) r = rng() % 3 != 0;
      for (uint32_t p : groups.rootPages) resident[p] = 1;
      for (int step = 0;; ++step) {
        QVERIFY(step < 64);
        const mesh::ResidentCut cut =
            mesh::selectResidentCut(pages.index, groups, viewer, [&](uint32_t p) { return resident[p] != 0; });
        QVERIFY(cut.rootsResident);
        for (uint32_t id : cut.clusters) QVERIFY(resident[pages.index.clusters[id].page]);
        for (const auto& [edge, n] : edgeUse(h_, inHierarchy(pages, cut.clusters)))
          if (n != 2) QFAIL(qPrintable(QString("trial %1 step %2: edge used %3 times").arg(trial).arg(step).arg(n)));
        for (uint32_t p : cut.wanted) QVERIFY(!resident[p]);
        if (cut.complete) {
          QVERIFY(cut.wanted.empty());
          QVERIFY(inHierarchy(pages, cut.clusters) == ideal);
          break;
        }
        incomplete += step == 0;
        QVERIFY(!cut.wanted.empty());
        resident[cut.wanted.front()] = 1;  // the most wanted page arrives
      }
    }
    QVERIFY(incomplete > 0);
    const mesh::ResidentCut none =
        mesh::selectResidentCut(pages.index, groups, viewer, [](uint32_t) { return false; });
    QVERIFY(!none.rootsResident && none.clusters.empty());
    QVERIFY(none.wanted == groups.rootPages);
  }

  // A group nobody sees is not refined: its finer pages are never asked for.
  void invisibleGroupsStayCoarse() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 8 << 10);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(pages.index);
    const mesh::CutViewer viewer{glm::vec3(0, -12, 0), 1000.0f, 0.5f};
    auto all = [](uint32_t) { return true; };
    // Only what lies on the viewer's side (y < 0) is seen.
    auto front = [](const mesh::LodSphere& s) { return s.centre.y - s.radius < 0.0f; };
    const mesh::ResidentCut seen = mesh::selectResidentCut(pages.index, groups, viewer, all, front);
    const mesh::ResidentCut everything = mesh::selectResidentCut(pages.index, groups, viewer, all);
    QVERIFY(seen.groupsRefined < everything.groupsRefined);
    // No hole; where nothing is seen a coarse cluster may overlap finer ones
    // (whatIsSeenIsAsFineAsWithoutVisibility).
    QCOMPARE(uncoveredVertices(h_, sphere_, inHierarchy(pages, seen.clusters)), size_t(0));
    // The check sees a hole: the full cut less its finest cluster.
    std::vector<uint32_t> holed = inHierarchy(pages, everything.clusters);
    const auto finest = std::min_element(holed.begin(), holed.end(), [&](uint32_t a, uint32_t b) {
      return h_.clusters[a].level < h_.clusters[b].level;
    });
    holed.erase(finest);
    QVERIFY(uncoveredVertices(h_, sphere_, holed) > 0);
    auto triangles = [&](const mesh::ResidentCut& c) {
      size_t n = 0;
      for (uint32_t id : c.clusters) n += pages.index.clusters[id].triangleCount;
      return n;
    };
    QVERIFY(triangles(seen) < triangles(everything));
  }

  // What is seen is as fine as without the visibility test: every seen
  // cluster the full cut draws is drawn, and a seen cluster drawn instead
  // is one whose finer clusters are all unseen; no hole anywhere, and seen
  // clusters overlap only where one of them stands for a group nobody sees
  // (drawn coarse beside the finer clusters of a seen group under it). The
  // walk first stopped at a group whose children nobody sees; the groups
  // under it that it shares with seen groups then never became ready, and
  // the seen part of the scan stayed coarse (a 4M-triangle valley drew a
  // tenth of its cut).
  void whatIsSeenIsAsFineAsWithoutVisibility() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 8 << 10);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(pages.index);
    auto all = [](uint32_t) { return true; };
    size_t views = 0, coarser = 0;
    for (const glm::vec3 eye : {glm::vec3(0, -12, 0), glm::vec3(3, -11, 4), glm::vec3(0, 0, 11)})
      for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0.6f, 0.0f, 0.8f)})
        for (float offset : {-4.0f, 0.0f, 3.0f}) {
          // Seen: what lies (partly) on one side of a plane.
          auto seen = [&](const mesh::LodSphere& b) { return glm::dot(b.centre, axis) - b.radius < offset; };
          const mesh::CutViewer viewer{eye, 1000.0f, 0.5f};
          const mesh::ResidentCut cut = mesh::selectResidentCut(pages.index, groups, viewer, all, seen);
          const mesh::ResidentCut full = mesh::selectResidentCut(pages.index, groups, viewer, all);
          const QString where = QString("eye (%1, %2, %3), plane %4").arg(eye.x).arg(eye.y).arg(eye.z).arg(offset);
          QVERIFY(cut.complete);
          QVERIFY2(uncoveredVertices(h_, sphere_, inHierarchy(pages, cut.clusters)) == 0, qPrintable(where + ": a hole"));
          // Seen clusters overlap only where one of them stands for a group
          // nobody sees (near the edge of what is seen).
          auto forUnseen = [&](uint32_t c) {
            const uint32_t g = pages.index.clusters[c].group;
            if (g == mesh::kNoGroup) return false;
            for (uint32_t k = groups.childrenFirst[g]; k < groups.childrenFirst[g + 1]; ++k)
              if (seen(pages.index.clusters[groups.children[k]].bounds)) return false;
            return true;
          };
          std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> users;  // edge -> seen clusters using it
          for (uint32_t c : cut.clusters) {
            if (!seen(pages.index.clusters[c].bounds)) continue;
            const mesh::Cluster& hc = h_.clusters[pages.order[c]];
            for (uint32_t t = 0; t < hc.triangleCount * 3; ++t) {
              auto& u = users[std::minmax(h_.indices[hc.firstIndex + t], h_.indices[hc.firstIndex + (t / 3) * 3 + (t + 1) % 3])];
              if (u.empty() || u.back() != c) u.push_back(c);
            }
          }
          for (const auto& [edge, us] : users)
            if (us.size() > 2)
              QVERIFY2(std::any_of(us.begin(), us.end(), forUnseen), qPrintable(where + ": seen clusters overlap"));
          const std::set<uint32_t> drawn(cut.clusters.begin(), cut.clusters.end());
          for (uint32_t c : full.clusters)
            if (seen(pages.index.clusters[c].bounds))
              QVERIFY2(drawn.count(c), qPrintable(where + QString(": seen cluster %1 not drawn").arg(c)));
          const std::set<uint32_t> fullSet(full.clusters.begin(), full.clusters.end());
          for (uint32_t c : cut.clusters) {
            if (!seen(pages.index.clusters[c].bounds) || fullSet.count(c)) continue;
            ++coarser;
            QVERIFY2(forUnseen(c), qPrintable(where + QString(": seen cluster %1 coarser than needed").arg(c)));
          }
          ++views;
        }
    qInfo("%zu views, %zu seen clusters coarser than the full cut's (their finer ones all unseen)", views, coarser);
  }

  // The walk tests only the groups under the roots and under the groups it
  // refines: from far away a handful, never the whole index; and with every
  // page resident its cut is the one each cluster's own test gives.
  void theCutCostsWhatItDraws() {
    const mesh::ClusterPages pages = mesh::paginate(h_, 8 << 10);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(pages.index);
    QVERIFY(!groups.topGroups.empty());
    auto all = [](uint32_t) { return true; };
    const mesh::ResidentCut far = mesh::selectResidentCut(pages.index, groups, {glm::vec3(1e5f, 0, 0), 1000.0f, 1.0f}, all);
    QCOMPARE(far.groupsRefined, size_t(0));
    QCOMPARE(far.groupsTested, groups.topGroups.size());
    QVERIFY(far.groupsTested * 10 < pages.index.groupCount);
    for (const glm::vec3 eye : {glm::vec3(0, -12, 0), glm::vec3(0, -40, 10), glm::vec3(200, 0, 0), glm::vec3(0, 0, 900)}) {
      const mesh::ResidentCut cut = mesh::selectResidentCut(pages.index, groups, {eye, 1000.0f, 1.0f}, all);
      // Refined: the groups the drawn clusters were simplified in, and every
      // group above a refined one (ids grow upwards).
      std::vector<uint8_t> refined(pages.index.groupCount, 0);
      for (uint32_t c : cut.clusters) {
        const uint32_t pg = pages.index.clusters[c].parentGroup;
        if (pg != mesh::kNoGroup) refined[pg] = 1;
      }
      for (uint32_t g = 0; g < pages.index.groupCount; ++g)
        for (uint32_t k = groups.madeFirst[g]; refined[g] && k < groups.madeFirst[g + 1]; ++k) {
          const uint32_t pg = pages.index.clusters[groups.made[k]].parentGroup;
          if (pg != mesh::kNoGroup) refined[pg] = 1;
        }
      QCOMPARE(size_t(std::count(refined.begin(), refined.end(), 1)), cut.groupsRefined);
      // Tested: exactly the groups whose clusters were all simplified in
      // refined groups (or are roots), each once.
      size_t expected = 0;
      for (uint32_t g = 0; g < pages.index.groupCount; ++g) {
        bool under = true;
        for (uint32_t k = groups.madeFirst[g]; k < groups.madeFirst[g + 1]; ++k) {
          const uint32_t pg = pages.index.clusters[groups.made[k]].parentGroup;
          under = under && (pg == mesh::kNoGroup || refined[pg]);
        }
        expected += under;
      }
      QCOMPARE(cut.groupsTested, expected);
      qInfo("eye (%g, %g, %g): %zu of %u groups tested, %zu refined", double(eye.x), double(eye.y), double(eye.z),
            cut.groupsTested, pages.index.groupCount, cut.groupsRefined);
      QVERIFY(inHierarchy(pages, cut.clusters) == mesh::selectClusterCut(h_, eye, 1000.0f, 1.0f));
    }
  }

  // Stored normals: unit, and on the bumpy sphere close to the radial direction.
  void pageNormals() {
    const mesh::ClusterPages pages = mesh::paginate(h_);
    double worst = 1.0;
    for (uint32_t p = 0; p < pages.index.pageCount; ++p) {
      std::string error;
      const auto clusters = mesh::decodeClusterPage(pages.pages[p].data(), pages.pages[p].size(), pages.index, p,
                                                    "normals", error);
      QVERIFY2(clusters, error.c_str());
      for (const auto& c : *clusters) {
        QCOMPARE(c.normals.size(), c.positions.size());
        for (size_t v = 0; v < c.normals.size(); ++v) {
          QVERIFY(std::abs(glm::length(c.normals[v]) - 1.0f) < 1e-4f);
          worst = std::min(worst, double(glm::dot(c.normals[v], glm::normalize(c.positions[v]))));
        }
      }
    }
    qInfo("smallest cosine between a stored normal and the radial direction: %.3f", worst);
    QVERIFY(worst > 0.5);
  }

  // Group ids that do not fit together are refused by name.
  void groupsAreChecked() {
    mesh::ClusterPages pages = mesh::paginate(h_);
    mesh::ClusterIndex bad = pages.index;
    size_t i = 0;
    while (bad.clusters[i].group == mesh::kNoGroup || bad.clusters[i].parentGroup == mesh::kNoGroup) ++i;
    bad.clusters[i].parentGroup = bad.clusters[i].group;
    QVERIFY2(mesh::clusterIndexProblem(bad).find("cluster " + std::to_string(i)) != std::string::npos,
             mesh::clusterIndexProblem(bad).c_str());
    bad = pages.index;
    bad.clusters[i].group = bad.groupCount + 3;
    QVERIFY(mesh::clusterIndexProblem(bad).find("group ids") != std::string::npos);
    QVERIFY(mesh::clusterIndexProblem(pages.index).empty());
  }

  void anEmptyMeshGivesNone() {
    mesh::ClusterBuildReport r;
    const ClusterHierarchy h = mesh::buildClusterHierarchy(mesh::MeshData{}, {}, &r);
    QVERIFY(h.clusters.empty() && h.indices.empty());
    QVERIFY(mesh::selectClusterCut(h, {0, 0, 0}, 1000.0f, 1.0f).empty());
  }
};

QTEST_GUILESS_MAIN(TestMeshprocClusters)
#include "test_meshproc_clusters.moc"
