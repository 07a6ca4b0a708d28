// The streamed (out-of-core) cluster hierarchy build (meshproc/
// cluster_build_streamed.h) on a bumpy closed sphere given as three tiles
// and cut into a dozen cells: the index it makes is sound (monotonic
// errors, groups in order: clusterIndexProblem), level 0 holds every input
// triangle, and every cut, whatever the viewer, is watertight by position
// (each edge used by exactly two triangles, as on the closed input) where
// clusters of different cells and levels meet; a coarse cut stays within
// its largest error of the input (sampled); level-0 normals along cell
// borders equal the input's own area-weighted normals (the halo); the
// pages and index come out byte for byte the same for one and two threads;
// the scratch folder is gone afterwards, and what a killed build left there
// is swept (this machine's dead processes' only); a tile that cannot be read, or
// tiles with no triangle, are errors naming the tile.
#include <QtTest>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <unordered_map>

#include "core/scratch_files.h"
#include "dead_scratch.h"
#include "mesh_builders.h"
#include "meshproc/cluster_build_streamed.h"
#include "meshproc/cluster_cut.h"
#include "meshproc/error_metrics.h"
#include "meshproc/position_key.h"

using namespace hs;

namespace {

// The sphere's triangles in three tiles by the angle of their centre (each
// tile with all the vertices, as a tile file would not be, but harmless).
std::vector<mesh::MeshData> tilesOf(const mesh::MeshData& m) {
  std::vector<mesh::MeshData> tiles(3);
  for (auto& t : tiles) {
    t.origin = m.origin;
    t.positions = m.positions;
  }
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    glm::vec3 c(0.0f);
    for (int k = 0; k < 3; ++k) c += m.positions[m.indices[f * 3 + size_t(k)]];
    const float a = std::atan2(c.y, c.x) + 3.14159265f;
    const size_t t = std::min<size_t>(2, size_t(a / (2.0f * 3.14159265f / 3.0f)));
    for (int k = 0; k < 3; ++k) tiles[t].indices.push_back(m.indices[f * 3 + size_t(k)]);
  }
  for (auto& t : tiles) t.submeshes.push_back({0, uint32_t(t.indices.size()), -1});
  return tiles;
}

struct Built {
  std::optional<mesh::ClusterIndex> index;
  std::vector<std::vector<uint8_t>> pages;
  mesh::StreamedClusterReport report;
  std::string error;
};

Built build(const std::vector<mesh::MeshData>& tiles, unsigned threads, const std::string& scratch = "") {
  std::vector<const mesh::MeshData*> p;
  for (const auto& t : tiles) p.push_back(&t);
  mesh::MeshTileSource source(p);
  mesh::StreamedClusterOptions o;
  o.cellTriangles = 1600;  // about a dozen cells on the 20k-triangle sphere
  o.clusters.threads = threads;
  o.scratchDir = scratch;
  Built b;
  b.index = mesh::buildClusterPagesStreamed(
      source, o,
      [&](std::vector<uint8_t>&& page, std::string&) {
        b.pages.push_back(std::move(page));
        return true;
      },
      &b.report, nullptr, b.error);
  return b;
}

// Every cluster of the index, decoded from its page.
std::vector<mesh::PageCluster> decodeAll(const Built& b) {
  std::vector<mesh::PageCluster> all(b.index->clusters.size());
  for (uint32_t p = 0; p < b.index->pageCount; ++p) {
    std::string error;
    auto clusters = mesh::decodeClusterPage(b.pages[p].data(), b.pages[p].size(), *b.index, p, "test", error);
    if (!clusters) qFatal("%s", error.c_str());
    for (auto& c : *clusters) all[c.cluster] = std::move(c);
  }
  return all;
}

// Position-pair edge -> uses among the cut's triangles.
std::map<std::pair<uint64_t, uint64_t>, int> edgeUse(const std::vector<mesh::PageCluster>& all,
                                                     const std::vector<uint32_t>& cut) {
  std::map<std::pair<uint64_t, uint64_t>, int> use;
  for (uint32_t id : cut) {
    const auto& c = all[id];
    for (size_t t = 0; t < c.triangles.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        const uint64_t a = mesh::positionKey(c.positions[c.triangles[t + size_t(k)]]);
        const uint64_t b = mesh::positionKey(c.positions[c.triangles[t + size_t((k + 1) % 3)]]);
        ++use[std::minmax(a, b)];
      }
  }
  return use;
}

std::vector<uint32_t> cutFor(const mesh::ClusterIndex& index, const mesh::ClusterGroups& groups, glm::vec3 eye,
                             float bound) {
  mesh::CutViewer v;
  v.eye = eye;
  v.focalPx = 500.0f;
  v.pixelBound = bound;
  return mesh::selectResidentCut(index, groups, v, [](uint32_t) { return true; }).clusters;
}

}  // namespace

class TestMeshprocStreamed : public QObject {
  Q_OBJECT
  mesh::MeshData sphere_;
  Built built_;

 private slots:
  void initTestCase() {
    sphere_ = test::bumpySphere();
    built_ = build(tilesOf(sphere_), 2);
    QVERIFY2(built_.index, built_.error.c_str());
    const auto& r = built_.report;
    qInfo("%zu tiles, %zu triangles, %zu cells, %zu border positions, %zu halo triangles, %zu levels, %zu clusters, "
          "%u pages, %zu roots",
          r.tiles, r.triangles, r.cells, r.borderPositions, r.haloTriangles, r.build.clustersPerLevel.size(),
          built_.index->clusters.size(), built_.index->pageCount, r.build.roots);
    QCOMPARE(r.tiles, size_t(3));
    QVERIFY(r.cells >= 8);
    QVERIFY(r.borderPositions > 0);
  }

  void levelZeroIsTheInput() {
    QCOMPARE(built_.report.triangles, sphere_.triangleCount());
    QCOMPARE(built_.report.build.trianglesPerLevel.front(), sphere_.triangleCount());
    size_t level0 = 0;
    for (const auto& e : built_.index->clusters)
      if (e.level == 0) level0 += e.triangleCount;
    QCOMPARE(level0, sphere_.triangleCount());
    // The cells met: one root group of clusters at the top, far fewer
    // triangles than the input.
    const auto& t = built_.report.build.trianglesPerLevel;
    QVERIFY(t.size() > 4);
    QVERIFY(t.back() * 20 < t.front());
    QVERIFY(built_.report.build.roots <= 4);
  }

  void everyCutIsWatertight() {
    const std::vector<mesh::PageCluster> all = decodeAll(built_);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(*built_.index);
    std::set<uint32_t> levelsSeen;
    for (const glm::vec3 eye : {glm::vec3(0, 0, 14), glm::vec3(25, 0, 0), glm::vec3(0, -60, 10), glm::vec3(400, 0, 0),
                                glm::vec3(11, 11, 0)})
      for (float bound : {0.25f, 1.0f, 4.0f}) {
        const std::vector<uint32_t> cut = cutFor(*built_.index, groups, eye, bound);
        QVERIFY(!cut.empty());
        for (uint32_t id : cut) levelsSeen.insert(built_.index->clusters[id].level);
        for (const auto& [edge, n] : edgeUse(all, cut))
          if (n != 2)
            QFAIL(qPrintable(QString("eye (%1, %2, %3), %4 px: an edge used %5 times (a crack or overlap)")
                                 .arg(eye.x).arg(eye.y).arg(eye.z).arg(bound).arg(n)));
      }
    qInfo("cuts drew levels 0 to %u", *levelsSeen.rbegin());
    QVERIFY(levelsSeen.size() > 3);  // mixed levels, across cells
  }

  void aCoarseCutStaysWithinItsError() {
    const std::vector<mesh::PageCluster> all = decodeAll(built_);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(*built_.index);
    const std::vector<uint32_t> cut = cutFor(*built_.index, groups, glm::vec3(0, -80, 0), 1.0f);
    mesh::MeshData m;
    float worst = 0.0f;
    size_t tris = 0;
    for (uint32_t id : cut) {
      worst = std::max(worst, built_.index->clusters[id].error);
      const uint32_t base = uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), all[id].positions.begin(), all[id].positions.end());
      for (uint8_t t : all[id].triangles) m.indices.push_back(base + t);
      tris += all[id].triangles.size() / 3;
    }
    m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
    const mesh::ErrorReport e = mesh::measureError(sphere_, m);
    qInfo("distant cut: %zu triangles of %zu, its largest error %.4f m, measured %.4f m", tris, sphere_.triangleCount(),
          double(worst), e.hausdorff);
    QVERIFY(tris * 4 < sphere_.triangleCount());
    QVERIFY(worst > 0.0f);
    QVERIFY(e.hausdorff <= double(worst) * 1.001 + 1e-6);
  }

  // Level 0's stored normals against the input's own (area-weighted by
  // position): equal along cell borders too, where each cell alone would
  // see only its side of the faces.
  void borderNormalsSeeBothSides() {
    std::unordered_map<uint64_t, glm::vec3> truth;
    for (size_t f = 0; f < sphere_.triangleCount(); ++f) {
      const glm::vec3* p[3];
      for (int k = 0; k < 3; ++k) p[k] = &sphere_.positions[sphere_.indices[f * 3 + size_t(k)]];
      const glm::vec3 n = glm::cross(*p[1] - *p[0], *p[2] - *p[0]);
      for (int k = 0; k < 3; ++k) truth[mesh::positionKey(*p[k])] += n;
    }
    const std::vector<mesh::PageCluster> all = decodeAll(built_);
    double worst = 1.0;
    for (const auto& c : all) {
      if (built_.index->clusters[c.cluster].level != 0) continue;
      for (size_t v = 0; v < c.positions.size(); ++v)
        worst = std::min(worst, double(glm::dot(c.normals[v], glm::normalize(truth.at(mesh::positionKey(c.positions[v]))))));
    }
    qInfo("level 0: smallest cosine between a stored normal and the input's: %.7f", worst);
    QVERIFY(worst > 0.99999);  // octahedral 16-bit: under 0.01 degrees
  }

  // Tiles each in a frame of their own (as a reader puts them, about their
  // own centres): their floats no longer agree along tile borders until
  // the border weld snaps them, and the cuts are watertight again.
  void tilesInTheirOwnFramesAreWelded() {
    std::vector<mesh::MeshData> tiles = tilesOf(sphere_);
    for (size_t k = 0; k < tiles.size(); ++k) {
      const glm::dvec3 offset(1000.37 * double(k), -777.1 * double(k), 3.3 * double(k));
      tiles[k].origin += offset;
      for (glm::vec3& p : tiles[k].positions) p = glm::vec3(glm::dvec3(p) - offset);
    }
    const Built b = build(tiles, 2);
    QVERIFY2(b.index, b.error.c_str());
    qInfo("%zu tile border vertices, %zu moved onto another tile's", b.report.tileBorderVertices,
          b.report.tileBorderVerticesSnapped);
    QVERIFY(b.report.tileBorderVerticesSnapped > 0);
    const std::vector<mesh::PageCluster> all = decodeAll(b);
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(*b.index);
    for (const glm::vec3 eye : {glm::vec3(0, 0, 14), glm::vec3(0, -60, 10)})
      for (const auto& [edge, n] : edgeUse(all, cutFor(*b.index, groups, eye, 1.0f))) QCOMPARE(n, 2);
  }

  void theSameForAnyThreadCount() {
    const std::string scratch = QDir::tempPath().toStdString() + "/hs-streamed-test";
    std::filesystem::create_directories(scratch);
    // What a killed build left (this machine, a process that is gone) is
    // swept; a live process's and another machine's (a shared folder) stay.
    const std::string live = scratchName("hs-clusters-");  // <host>-<this pid>-<n>
    const test::DeadScratch dead = test::asDeadProcess(live);
    QVERIFY(!dead.name.empty());
    const std::string& stale = dead.name;
    const std::string elsewhere = "hs-clusters-render-node-7-" + std::to_string(dead.pid) + "-0";
    for (const std::string& name : {live, stale, elsewhere}) {
      std::filesystem::create_directories(scratch + "/" + name);
      std::ofstream(scratch + "/" + name + "/triangles.bin") << "left behind";
    }
    const Built one = build(tilesOf(sphere_), 1, scratch);
    QVERIFY(!std::filesystem::exists(scratch + "/" + stale));
    QVERIFY(std::filesystem::exists(scratch + "/" + live + "/triangles.bin"));
    QVERIFY(std::filesystem::exists(scratch + "/" + elsewhere + "/triangles.bin"));
    std::filesystem::remove_all(scratch + "/" + live);
    std::filesystem::remove_all(scratch + "/" + elsewhere);
    QVERIFY2(one.index, one.error.c_str());
    QCOMPARE(one.pages.size(), built_.pages.size());
    QVERIFY(one.pages == built_.pages);
    QVERIFY(mesh::encodeClusterIndex(*one.index) == mesh::encodeClusterIndex(*built_.index));
    // Nothing left behind in the scratch folder.
    QVERIFY(std::filesystem::is_empty(scratch));
    std::filesystem::remove_all(scratch);
  }

  void badTilesAreNamed() {
    class Failing : public mesh::ScanTileSource {
     public:
      size_t tileCount() const override { return 2; }
      bool readTile(size_t i, mesh::MeshData& out, std::string& error) override {
        if (i == 1) {
          error = "tiles/b.ply: truncated at byte 120";
          return false;
        }
        out = test::icosphere(2, 1.0);
        return true;
      }
    } failing;
    std::string error;
    auto index = mesh::buildClusterPagesStreamed(
        failing, {}, [](std::vector<uint8_t>&&, std::string&) { return true; }, nullptr, nullptr, error);
    QVERIFY(!index);
    QCOMPARE(QString::fromStdString(error), QString("tiles/b.ply: truncated at byte 120"));

    mesh::MeshData empty;
    mesh::MeshTileSource none({&empty});
    index = mesh::buildClusterPagesStreamed(
        none, {}, [](std::vector<uint8_t>&&, std::string&) { return true; }, nullptr, nullptr, error);
    QVERIFY(!index);
    QVERIFY2(error.find("no triangle") != std::string::npos, error.c_str());

    // A sink that cannot write stops the build with its message.
    const std::vector<mesh::MeshData> tiles = tilesOf(sphere_);
    mesh::MeshTileSource source({&tiles[0], &tiles[1], &tiles[2]});
    mesh::StreamedClusterOptions o;
    o.cellTriangles = 1600;
    index = mesh::buildClusterPagesStreamed(
        source, o,
        [](std::vector<uint8_t>&&, std::string& e) {
          e = "pages.bin: disk full";
          return false;
        },
        nullptr, nullptr, error);
    QVERIFY(!index);
    QCOMPARE(QString::fromStdString(error), QString("pages.bin: disk full"));
  }
};

QTEST_GUILESS_MAIN(TestMeshprocStreamed)
#include "test_meshproc_streamed.moc"
