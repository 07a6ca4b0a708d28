// OGC 3D Tiles import (issue 38 item 5; mesh/tileset_reader.h,
// meshproc/cluster_from_tiles.h, scene/tileset_import.h): a tileset the
// test writes itself (a b3dm root with RTC_CENTER over two children, a
// plain glb and a Draco-compressed glb, under an east-north-up transform
// at Meteora) comes in as a two-level cluster hierarchy whose vertices lie
// where WGS 84 and UTM put them, computed here by an independent path
// (Bowring's ECEF to latitude/longitude, then OGR's UTM, against the
// import's one PROJ step from ECEF); the cut takes the root from afar and
// the children close up; ADD refinement, empty tiles, errors that shrink
// up the tree. Bad input: a missing content file, a cyclic external
// tileset, an unknown and a point-cloud format, a truncated b3dm, a broken
// glb, a tileset that is not JSON or holds nothing: named, and what is
// left comes in (or, with nothing left, the scene is untouched). Streamed
// (`--clusters streamed`): the leaves alone decoded one at a time into a
// hierarchy built here, at the same UTM places; a missing leaf keeps its
// parent whole as in core.
#include <ogr_srs_api.h>

#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <set>

#include "cli_runner.h"
#include "cluster_vertices.h"
#include "file_bytes.h"
#include "tileset_files.h"
#include "core/json.h"
#include "meshproc/cluster_cut.h"
#include "meshproc/cluster_from_tiles.h"
#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

namespace {

constexpr double kLon = 21.6300, kLat = 39.7217, kHeight = 300.0;  // Meteora
constexpr float kRootError = 20.0f;
const glm::dvec3 kRtc(50.0, 20.0, 0.0);

double bumps(double e, double n) { return 4.0 * std::sin(e / 30.0) * std::cos(n / 40.0); }
test::TestGrid coarse() { return test::testGrid(-100, 100, -100, 100, 2, bumps); }
test::TestGrid west() { return test::testGrid(-100, 0, -100, 100, 8, bumps); }
test::TestGrid east() { return test::testGrid(0, 100, -100, 100, 8, bumps); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

// UTM zone 34N of a point of the ENU frame, the test's own way.
glm::dvec3 expectedUtm(const glm::dvec3& enu) {
  const glm::dvec3 ecef = glm::dvec3(test::enuToEcef(kLon, kLat, kHeight) * glm::dvec4(enu, 1.0));
  const glm::dvec3 geo = test::ecefToGeodetic(ecef);
  OGRSpatialReferenceH from = OSRNewSpatialReference(nullptr), to = OSRNewSpatialReference(nullptr);
  OSRSetFromUserInput(from, "EPSG:4326");
  OSRSetFromUserInput(to, "EPSG:32634");
  OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
  OSRSetAxisMappingStrategy(to, OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(from, to);
  double x = geo.x, y = geo.y, z = 0.0;
  OCTTransform(t, 1, &x, &y, &z);
  OCTDestroyCoordinateTransformation(t);
  OSRDestroySpatialReference(from);
  OSRDestroySpatialReference(to);
  return {x, y, geo.z};
}

Json tile(const std::string& uri, double error, Json children = Json::array()) {
  Json t = {{"boundingVolume", {{"sphere", {0, 0, 0, 200}}}}, {"geometricError", error}};
  if (!uri.empty()) t["content"] = {{"uri", uri}};
  if (!children.empty()) t["children"] = std::move(children);
  return t;
}

Json tilesetOf(Json root) {
  root["transform"] = test::matrixJson(test::enuToEcef(kLon, kLat, kHeight));
  if (!root.contains("refine")) root["refine"] = "REPLACE";
  return {{"asset", {{"version", "1.0"}}}, {"geometricError", 100}, {"root", std::move(root)}};
}


}  // namespace

class TestTilesetImport : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

  std::string dir(const std::string& name) const {
    const fs::path d = fs::path(tmp_.path().toStdString()) / name;
    fs::create_directories(d);
    return d.string();
  }
  // The good tileset's files into `d` (its root and two children).
  void writeContents(const std::string& d) const {
    test::writeBytes(d + "/root.b3dm", test::b3dmOf(test::glbOf(coarse(), kRtc), kRtc));
    test::writeBytes(d + "/a.glb", test::glbOf(west()));
    test::writeBytes(d + "/b.glb", test::glbOf(east(), glm::dvec3(0.0), true));
  }
  std::string goodTileset() const {
    const std::string d = dir("good");
    writeContents(d);
    test::writeText(d + "/tileset.json",
                    tilesetOf(tile("root.b3dm", kRootError, {tile("a.glb", 0), tile("b.glb", 0)})).dump(1));
    return d + "/tileset.json";
  }
  static ImportedMesh imported(const std::string& path) {
    MeshImportRequest r;
    r.files = {path};
    return importMeshFiles(r);
  }

 private slots:
  void importsHierarchy() {
    const ImportedMesh m = imported(goodTileset());
    QVERIFY2(m.ok(), m.error.c_str());
    QVERIFY2(m.import.warnings.empty(), joined(m.import.warnings).c_str());
    QVERIFY(m.clusters);
    QCOMPARE(m.import.reader, std::string("3dtiles"));
    QCOMPARE(m.import.geoOffsetCrs, std::string("EPSG:32634"));
    QVERIFY2(contains(m.import.geoOffsetSource, "UTM zone 34N"), m.import.geoOffsetSource.c_str());
    const mesh::ClusterIndex& index = m.clusters->index;
    QCOMPARE(m.clusters->levels(), size_t(2));
    QCOMPARE(index.groupCount, 1u);
    QCOMPARE(m.clusters->triangles(0), west().triangles.size() / 3 + east().triangles.size() / 3);
    QCOMPARE(m.clusters->triangles(1), coarse().triangles.size() / 3);
    for (const mesh::ClusterIndexEntry& e : index.clusters) {
      if (e.level == 1) {
        QCOMPARE(e.error, kRootError);
        QVERIFY(std::isinf(e.parentError));
      } else {
        QCOMPARE(e.error, 0.0f);
        QCOMPARE(e.parentError, kRootError);
      }
    }
    mesh::ClusterIndex copy = index;
    QCOMPARE(mesh::clusterIndexProblem(copy), std::string());
    // Every triangle the file declares came in.
    QCOMPARE(m.import.trianglesOut, m.import.declaredTriangles);
    QCOMPARE(m.import.trianglesOut, (coarse().triangles.size() + west().triangles.size() + east().triangles.size()) / 3);
  }

  void placesVerticesInUtm() {
    const ImportedMesh m = imported(goodTileset());
    QVERIFY2(m.ok(), m.error.c_str());
    const std::vector<glm::dvec3> fine = test::clusterLevelVertices(*m.clusters, 0), root = test::clusterLevelVertices(*m.clusters, 1);
    double worst = 0.0;
    for (const test::TestGrid& g : {west(), east()})  // the plain glb and the Draco one
      for (const glm::dvec3& p : g.points) worst = std::max(worst, test::nearestOf(fine, expectedUtm(p), 1.0));
    for (const glm::dvec3& p : coarse().points)  // b3dm with RTC_CENTER
      worst = std::max(worst, test::nearestOf(root, expectedUtm(p), 1.0));
    // Float positions about an origin in the middle: 200 m spans resolve to
    // about 10 micrometres; PROJ and Bowring agree far closer than that.
    QVERIFY2(worst < 1e-3, qPrintable(QString("largest distance from the expected UTM position: %1 m").arg(worst)));
    // Nothing else: as many distinct vertices as the grids have.
    QVERIFY(fine.size() >= west().points.size() + east().points.size() - 9);
  }

  void cutTakesRootFarChildrenNear() {
    const ImportedMesh m = imported(goodTileset());
    QVERIFY2(m.ok(), m.error.c_str());
    const mesh::ClusterIndex& index = m.clusters->index;
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(index);
    auto levelsOf = [&](glm::vec3 eye) {
      const mesh::ResidentCut cut =
          mesh::selectResidentCut(index, groups, {eye, 1000.0f, 1.0f}, [](uint32_t) { return true; });
      std::set<uint32_t> levels;
      for (uint32_t c : cut.clusters) levels.insert(index.clusters[c].level);
      return levels;
    };
    // 20 m over 1000 px at 40 km: half a pixel (the root); at 50 m: 400 px.
    QCOMPARE(levelsOf({0, 0, 40000}), std::set<uint32_t>{1});
    QCOMPARE(levelsOf({0, 0, 50}), std::set<uint32_t>{0});
  }

  void additiveEmptyAndShrinkingErrors() {
    // Tiles made here: an ADD root (error 2) over a tile with no content
    // (error 5, passed through: the leaves hang under the root) over two
    // leaves.
    auto lod = [](const test::TestGrid& g, int parent, float error, bool add) {
      mesh::LodTile t;
      t.parent = parent, t.error = error, t.additive = add;
      for (const glm::dvec3& p : g.points) t.positions.emplace_back(p);
      t.indices = g.triangles;
      return t;
    };
    std::vector<mesh::LodTile> tiles = {lod(coarse(), -1, 2.0f, true), mesh::LodTile{}, lod(west(), 1, 0.0f, false),
                                        lod(east(), 1, 0.0f, false)};
    tiles[1].parent = 0, tiles[1].error = 5.0f;
    mesh::TileHierarchyReport report;
    const mesh::ClusterHierarchy h = mesh::clusterHierarchyOfTiles(tiles, glm::dvec3(0.0), {}, &report);
    QCOMPARE(report.tilesWithContent, size_t(3));
    QCOMPARE(report.tilesPassedThrough, size_t(1));
    QCOMPARE(report.additiveCopies, size_t(1));
    QCOMPARE(report.errorsRaised, size_t(0));  // the empty tile's error is not the root's
    mesh::ClusterPages pages = mesh::paginate(h);
    QCOMPARE(mesh::clusterIndexProblem(pages.index), std::string());
    // Near: the leaves and the root's ADD copy; far: the root alone.
    auto triangles = [&](glm::vec3 eye) {
      return mesh::summariseCut(h, mesh::selectClusterCut(h, eye, 1000.0f, 1.0f)).triangles;
    };
    const size_t rootTris = coarse().triangles.size() / 3, leafTris = (west().triangles.size() + east().triangles.size()) / 3;
    QCOMPARE(triangles({0, 0, 50}), leafTris + rootTris);
    QCOMPARE(triangles({0, 0, 1e6f}), rootTris);
    // An error below its children's is raised to theirs, and said.
    tiles = {lod(coarse(), -1, 1.0f, false), lod(west(), 0, 0.0f, false), lod(east(), 0, 0.0f, false)};
    tiles.push_back(lod(west(), 1, 0.0f, false));
    tiles[1].error = 4.0f;  // the west tile now has a child: its group's error is 4, over the root's 1
    const mesh::ClusterHierarchy raised = mesh::clusterHierarchyOfTiles(tiles, glm::dvec3(0.0), {}, &report);
    QCOMPARE(report.errorsRaised, size_t(1));
    QVERIFY(!report.warnings.empty());
    pages = mesh::paginate(raised);
    QCOMPARE(mesh::clusterIndexProblem(pages.index), std::string());
  }

  void missingContentKeepsParentWhole() {
    const std::string d = dir("missing");
    writeContents(d);
    test::writeText(d + "/tileset.json",
                    tilesetOf(tile("root.b3dm", kRootError, {tile("a.glb", 0), tile("gone.glb", 0)})).dump());
    const ImportedMesh m = imported(d + "/tileset.json");
    QVERIFY2(m.ok(), m.error.c_str());
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "gone.glb") && contains(w, "is missing"), w.c_str());
    QVERIFY2(contains(w, "kept at its own level"), w.c_str());
    // Refining the root would leave the east half open: the root is all there is.
    QCOMPARE(m.clusters->levels(), size_t(1));
    QCOMPARE(m.clusters->triangles(0), coarse().triangles.size() / 3);
  }

  void cyclicTilesetIsNotFollowed() {
    const std::string d = dir("cycle");
    writeContents(d);
    // tileset.json -> sub.json -> tileset.json
    test::writeText(d + "/tileset.json", tilesetOf(tile("root.b3dm", kRootError, {tile("sub.json", 10)})).dump());
    test::writeText(d + "/sub.json",
                    Json{{"asset", {{"version", "1.0"}}},
                         {"root", tile("", 10, {tile("a.glb", 0), tile("b.glb", 0), tile("tileset.json", 0)})}}
                        .dump());
    const ImportedMesh m = imported(d + "/tileset.json");
    QVERIFY2(m.ok(), m.error.c_str());
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "cycle") && contains(w, "sub.json") && contains(w, "tileset.json"), w.c_str());
    QVERIFY(m.clusters->levels() >= 1);
  }

  void unknownAndPointFormatsAreNamed() {
    const std::string d = dir("formats");
    writeContents(d);
    test::writeText(d + "/strange.tile", "HSXX not a tile at all");
    test::writeText(d + "/cloud.pnts", "pnts....");
    test::writeText(d + "/tileset.json",
                    tilesetOf(tile("", 30, {tile("root.b3dm", kRootError, {tile("a.glb", 0), tile("b.glb", 0)}),
                                            tile("strange.tile", 0), tile("cloud.pnts", 0)}))
                        .dump());
    const ImportedMesh m = imported(d + "/tileset.json");
    QVERIFY2(m.ok(), m.error.c_str());
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "strange.tile: an unknown tile format"), w.c_str());
    QVERIFY2(contains(w, "cloud.pnts: pnts content"), w.c_str());
    QCOMPARE(m.clusters->levels(), size_t(2));  // the good subtree in whole
  }

  void truncatedAndBrokenContent() {
    const std::string d = dir("broken");
    writeContents(d);
    std::vector<uint8_t> b3dm = test::b3dmOf(test::glbOf(coarse(), kRtc), kRtc);
    b3dm.resize(b3dm.size() / 2);
    test::writeBytes(d + "/root.b3dm", b3dm);
    std::vector<uint8_t> glb = test::glbOf(west());
    for (size_t i = 20; i < 60 && i < glb.size(); ++i) glb[i] = 0xEE;  // its JSON chunk
    test::writeBytes(d + "/a.glb", glb);
    test::writeText(d + "/tileset.json",
                    tilesetOf(tile("root.b3dm", kRootError, {tile("a.glb", 0), tile("b.glb", 0)})).dump());
    const ImportedMesh m = imported(d + "/tileset.json");
    QVERIFY2(m.ok(), m.error.c_str());
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "root.b3dm: a b3dm whose header is truncated"), w.c_str());
    QVERIFY2(contains(w, "a.glb: not a readable glTF asset"), w.c_str());
    // The root had no content left and passes its children through: b alone.
    QCOMPARE(m.clusters->levels(), size_t(1));
    QCOMPARE(m.clusters->triangles(0), east().triangles.size() / 3);
  }

  void unreadableTilesetsAreErrors() {
    const std::string d = dir("errors");
    test::writeText(d + "/bad.json", "{\"asset\": {\"version\": \"1.0\"}, \"root\": {");
    ImportedMesh m = imported(d + "/bad.json");
    QVERIFY(!m.ok());
    QVERIFY2(contains(m.error, "bad.json") && contains(m.error, "line"), m.error.c_str());
    test::writeText(d + "/empty.json", tilesetOf(tile("nothing.glb", 0)).dump());
    m = imported(d + "/empty.json");
    QVERIFY(!m.ok());
    QVERIFY2(contains(m.error, "empty.json: no triangles came in") && contains(m.error, "nothing.glb"),
             m.error.c_str());
    MeshImportRequest off;
    off.files = {goodTileset()};
    off.clusters = MeshImportRequest::Clusters::Off;
    m = importMeshFiles(off);
    QVERIFY2(!m.ok() && contains(m.error, "--clusters off"), m.error.c_str());
  }

  void streamedBuildsFromTheFinestTiles() {
    // Out of core: the tree read without decoding, the leaves decoded one
    // at a time into a hierarchy built here; the root's coarse content unused.
    MeshImportRequest r;
    r.files = {goodTileset()};
    r.clusters = MeshImportRequest::Clusters::Streamed;
    const ImportedMesh m = importMeshFiles(r);
    QVERIFY2(m.ok(), m.error.c_str());
    QVERIFY(m.streamed);
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "built out of core from the 2 contents of its full detail (1 coarser"), w.c_str());
    QCOMPARE(m.import.geoOffsetCrs, std::string("EPSG:32634"));
    QCOMPARE(m.clusters->triangles(0), (west().triangles.size() + east().triangles.size()) / 3);
    QVERIFY(m.clusters->levels() >= 2);
    mesh::ClusterIndex copy = m.clusters->index;
    QCOMPARE(mesh::clusterIndexProblem(copy), std::string());
    // Level 0 is the two leaves, where WGS 84 and UTM put them, both ways:
    // every grid point has a vertex and every vertex a grid point.
    const std::vector<glm::dvec3> fine = test::clusterLevelVertices(*m.clusters, 0);
    std::vector<glm::dvec3> expected;
    for (const test::TestGrid& g : {west(), east()})
      for (const glm::dvec3& p : g.points) expected.push_back(expectedUtm(p));
    std::sort(expected.begin(), expected.end(), [](const glm::dvec3& a, const glm::dvec3& b) { return a.x < b.x; });
    double worst = 0.0;
    for (const glm::dvec3& p : expected) worst = std::max(worst, test::nearestOf(fine, p, 1.0));
    for (const glm::dvec3& p : fine) worst = std::max(worst, test::nearestOf(expected, p, 1.0));
    QVERIFY2(worst < 1e-3, qPrintable(QString("largest distance from the expected UTM position: %1 m").arg(worst)));
  }

  void streamedMissingLeafKeepsParentWhole() {
    const std::string d = dir("streamed-missing");
    writeContents(d);
    test::writeText(d + "/tileset.json",
                    tilesetOf(tile("root.b3dm", kRootError, {tile("a.glb", 0), tile("gone.glb", 0)})).dump());
    MeshImportRequest r;
    r.files = {d + "/tileset.json"};
    r.clusters = MeshImportRequest::Clusters::Streamed;
    const ImportedMesh m = importMeshFiles(r);
    QVERIFY2(m.ok(), m.error.c_str());
    const std::string w = joined(m.import.warnings);
    QVERIFY2(contains(w, "gone.glb") && contains(w, "is missing"), w.c_str());
    QVERIFY2(contains(w, "root.b3dm: kept at its own level everywhere"), w.c_str());
    // The root alone, as in core: refining it would open the east half.
    QCOMPARE(m.clusters->triangles(0), coarse().triangles.size() / 3);
  }

  void cliImportInfoRender() {
    const QString scene = tmp_.path() + "/cli.hscene";
    QCOMPARE(test::runCli({"new", scene}, tmp_.path()).code, 0);
    test::CliRun c = test::runCli({"import", QString::fromStdString(goodTileset()), scene}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("cluster hierarchy:"), qPrintable(c.out));
    c = test::runCli({"info", scene, "--json"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json info = Json::parse(c.out.toStdString());
    const Json& clusters = info.at("assets").at(0).at("clusters");
    QCOMPARE(clusters.at("levels").get<size_t>(), size_t(2));
    QCOMPARE(clusters.at("triangles").get<size_t>(), (west().triangles.size() + east().triangles.size()) / 3);
    // A tileset with nothing in it: refused, naming it; the scene keeps its one asset.
    const std::string d = dir("cli-empty");
    test::writeText(d + "/tileset.json", tilesetOf(tile("nothing.glb", 0)).dump());
    c = test::runCli({"import", QString::fromStdString(d + "/tileset.json"), scene}, tmp_.path());
    QVERIFY(c.code != 0);
    QVERIFY2(c.err.contains("tileset.json: no triangles came in"), qPrintable(c.err));
    c = test::runCli({"info", scene, "--json"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QCOMPARE(Json::parse(c.out.toStdString()).at("assets").size(), size_t(1));
    // It renders, waiting for the cut's pages (the scan moved from its UTM
    // place to before the scene's camera).
    c = test::runCli({"set", "good", "transform.translation", "0,150,-10", scene}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const QString png = tmp_.path() + "/cli.png", stats = tmp_.path() + "/cli.json";
    c = test::runCli({"render", scene, "--out", png, "--size", "160x120", "--stats", stats}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json frame = Json::parse(hs::test::readFile(stats.toStdString()));
    QVERIFY2(frame.at("clusters").at("complete").get<bool>(), frame.dump().c_str());
  }
};

QTEST_GUILESS_MAIN(TestTilesetImport)
#include "test_tileset_import.moc"
