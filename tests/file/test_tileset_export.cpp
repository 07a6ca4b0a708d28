// OGC 3D Tiles export (issue 38 item 5; mesh/tileset_writer.h,
// scene/tileset_export.h): a clustered scan written as a tile tree of
// uniform cuts reads back (through the project's reader, and its JSON
// checked against the 3D Tiles rules: boxes holding content and children,
// errors shrinking down the tree) with every level-0 triangle in exactly
// one leaf; a LOD chain as nested tiles; a tileset imported in UTM,
// exported to ECEF and imported again lands where it was, to the
// millimetre, through the real CLI.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>

#include "cli_runner.h"
#include "cluster_vertices.h"
#include "file_bytes.h"
#include "tileset_files.h"
#include "core/json.h"
#include "mesh/tileset_reader.h"
#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"
#include "scene/tileset_export.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";
constexpr double kLon = 21.6300, kLat = 39.7217, kHeight = 300.0;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

MeshAsset assetOf(ImportedMesh m, const std::string& name) {
  MeshAsset a;
  a.name = name;
  a.data = std::make_shared<const mesh::MeshData>(std::move(*m.mesh));
  a.lods = std::move(m.lods);
  a.clusters = std::move(m.clusters);
  a.importReport = m.importReport;
  return a;
}

struct Box {
  glm::dvec3 lo, hi;
};
Box boxOf(const Json& v) {
  const Json& b = v.at("box");
  const glm::dvec3 c(b[0].get<double>(), b[1].get<double>(), b[2].get<double>());
  const glm::dvec3 h(b[3].get<double>(), b[7].get<double>(), b[11].get<double>());
  return {c - h, c + h};
}
bool inside(const Box& inner, const Box& outer) {
  const double e = 1e-6;
  return glm::all(glm::greaterThanEqual(inner.lo, outer.lo - e)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi + e));
}

// Every tile's rules: its box holds its children's, their errors are at
// most its own. Counts tiles and the depth.
void checkTree(const Json& t, size_t depth, size_t& tiles, size_t& deepest, std::string& problem) {
  ++tiles;
  deepest = std::max(deepest, depth);
  const Box box = boxOf(t.at("boundingVolume"));
  if (!t.contains("children")) return;
  for (const Json& c : t.at("children")) {
    if (!inside(boxOf(c.at("boundingVolume")), box)) problem = "a child's box is outside its parent's";
    if (c.at("geometricError").get<double>() > t.at("geometricError").get<double>())
      problem = "a child's geometric error is larger than its parent's";
    checkTree(c, depth + 1, tiles, deepest, problem);
  }
}

}  // namespace

class TestTilesetExport : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

  std::string dir(const std::string& name) const {
    const fs::path d = fs::path(tmp_.path().toStdString()) / name;
    fs::create_directories(d);
    return d.string();
  }

 private slots:
  void clusteredScanAsTileTree() {
    MeshImportRequest r;
    r.files = {kBunny};
    r.clusters = MeshImportRequest::Clusters::On;
    ImportedMesh m = importMeshFiles(r);
    QVERIFY2(m.ok(), m.error.c_str());
    const size_t bunnyTriangles = m.clusters->triangles(0);
    const MeshAsset asset = assetOf(std::move(m), "Bunny");
    const std::string path = dir("bunny") + "/tileset.json";
    TilesetExportOptions o;
    o.maxTileTriangles = 8000;  // the bunny's 70k triangles over several leaves
    std::vector<std::string> notes;
    const mesh::ExportResult w = exportTileset(asset, path, o, notes);
    QVERIFY2(w.ok(), w.error.c_str());
    QVERIFY(!notes.empty() && contains(notes.front(), "not placed on the globe"));  // the bunny has no CRS
    // The JSON by the rules.
    const Json doc = Json::parse(hs::test::readFile(path));
    QCOMPARE(doc.at("asset").at("version").get<std::string>(), std::string("1.1"));
    size_t tiles = 0, deepest = 0;
    std::string problem;
    checkTree(doc.at("root"), 0, tiles, deepest, problem);
    QVERIFY2(problem.empty(), problem.c_str());
    QVERIFY2(deepest >= 3, qPrintable(QString("depth %1").arg(deepest)));
    QVERIFY(doc.at("geometricError").get<double>() >= doc.at("root").at("geometricError").get<double>());
    // Read back: the leaves (error 0) hold level 0, each triangle once.
    mesh::Tileset back;
    std::string error;
    QVERIFY2(mesh::readTileset(path, back, error), error.c_str());
    QVERIFY2(back.warnings.empty(), back.warnings.empty() ? "" : back.warnings.front().c_str());
    QCOMPARE(back.contentsRead, back.contentsDeclared);
    std::vector<uint8_t> hasChild(back.tiles.size(), 0);
    for (const mesh::TilesetTile& t : back.tiles)
      if (t.parent >= 0) hasChild[size_t(t.parent)] = 1;
    size_t leafTriangles = 0;
    for (size_t i = 0; i < back.tiles.size(); ++i)
      if (!hasChild[i]) {
        QCOMPARE(back.tiles[i].geometricError, 0.0);
        leafTriangles += back.tiles[i].indices.size() / 3;
      }
    QCOMPARE(leafTriangles, bunnyTriangles);
    // Leaves' vertices are the scan's own, where the asset has them (its
    // local frame: the root's transform is the origin).
    const std::vector<glm::dvec3> level0 = test::clusterLevelVertices(*asset.clusters, 0);
    double worst = 0.0;
    size_t checked = 0;
    for (size_t i = 0; i < back.tiles.size(); ++i) {
      if (hasChild[i]) continue;
      for (size_t v = 0; v < back.tiles[i].positions.size(); v += 97, ++checked) {
        worst = std::max(worst, test::nearestOf(level0, back.tiles[i].positions[v], 1e-3));
      }
    }
    QVERIFY(checked > 100);
    QVERIFY2(worst < 1e-5, qPrintable(QString("a leaf vertex %1 m from the scan's").arg(worst)));
  }

  void dracoContentWithinItsReportedError() {
    // The same tree with Draco content (14-bit positions): read back through
    // the reader's own Draco decoding, every leaf vertex lies within the
    // reported quantization error of the scan's, the error is what a 14-bit
    // grid over a tile can give, and the files are smaller.
    MeshImportRequest r;
    r.files = {kBunny};
    r.clusters = MeshImportRequest::Clusters::On;
    ImportedMesh m = importMeshFiles(r);
    QVERIFY2(m.ok(), m.error.c_str());
    const MeshAsset asset = assetOf(std::move(m), "Bunny");
    auto bytesOf = [](const mesh::ExportResult& w) {
      uintmax_t total = 0;
      for (const std::string& f : w.written) total += fs::file_size(f);
      return total;
    };
    TilesetExportOptions o;
    o.maxTileTriangles = 8000;
    std::vector<std::string> notes;
    const mesh::ExportResult exact = exportTileset(asset, dir("exact") + "/tileset.json", o, notes);
    QVERIFY2(exact.ok(), exact.error.c_str());
    QCOMPARE(exact.quantizationError, 0.0);
    o.dracoBits = 14;
    const std::string path = dir("draco") + "/tileset.json";
    const mesh::ExportResult w = exportTileset(asset, path, o, notes);
    QVERIFY2(w.ok(), w.error.c_str());
    QCOMPARE(w.triangles, exact.triangles);
    // Half a step of a 14-bit grid over the bunny's largest extent, on each axis.
    const mesh::Bounds b = asset.data->bounds();
    const glm::dvec3 extent = b.max - b.min;
    const double bound = std::max({extent.x, extent.y, extent.z}) / ((1 << 14) - 1) * 0.5 * std::sqrt(3.0);
    QVERIFY2(w.quantizationError > 0.0 && w.quantizationError <= bound * 1.001,
             qPrintable(QString("reported %1 m, a 14-bit grid allows %2 m").arg(w.quantizationError).arg(bound)));
    QVERIFY2(bytesOf(w) < bytesOf(exact) / 2,
             qPrintable(QString("Draco %1 bytes, exact %2").arg(bytesOf(w)).arg(bytesOf(exact))));
    mesh::Tileset back;
    std::string error;
    QVERIFY2(mesh::readTileset(path, back, error), error.c_str());
    QVERIFY2(back.warnings.empty(), back.warnings.empty() ? "" : back.warnings.front().c_str());
    const std::vector<glm::dvec3> level0 = test::clusterLevelVertices(*asset.clusters, 0);
    std::vector<uint8_t> hasChild(back.tiles.size(), 0);
    for (const mesh::TilesetTile& t : back.tiles)
      if (t.parent >= 0) hasChild[size_t(t.parent)] = 1;
    double worst = 0.0;
    size_t checked = 0, leafTriangles = 0;
    const double reach = w.quantizationError + 1e-6;
    for (size_t i = 0; i < back.tiles.size(); ++i) {
      if (hasChild[i]) continue;
      leafTriangles += back.tiles[i].indices.size() / 3;
      for (size_t v = 0; v < back.tiles[i].positions.size(); v += 7, ++checked) {
        worst = std::max(worst, test::nearestOf(level0, back.tiles[i].positions[v], reach));
      }
    }
    QCOMPARE(leafTriangles, asset.clusters->triangles(0));
    QVERIFY(checked > 1000);
    // Float positions about each tile's centre add their own rounding (a
    // few tenths of a micrometre at the bunny's size).
    QVERIFY2(worst <= w.quantizationError + 1e-6,
             qPrintable(QString("a decoded vertex %1 m from the scan's; reported %2 m").arg(worst).arg(w.quantizationError)));
    QVERIFY2(worst > 0.25 * w.quantizationError, qPrintable(QString("measured %1 m, reported %2 m: the report "
                                                                     "overstates").arg(worst).arg(w.quantizationError)));
  }

  void lodChainAsNestedTiles() {
    MeshImportRequest r;
    r.files = {kBunny};
    r.clusters = MeshImportRequest::Clusters::Off;
    r.process = true;
    r.processing.lodLevels = 2;
    ImportedMesh m = importMeshFiles(r);
    QVERIFY2(m.ok(), m.error.c_str());
    QCOMPARE(m.lods.size(), size_t(2));
    const MeshAsset asset = assetOf(std::move(m), "Bunny LODs");
    const std::string path = dir("chain") + "/tileset.json";
    std::vector<std::string> notes;
    const mesh::ExportResult w = exportTileset(asset, path, {}, notes);
    QVERIFY2(w.ok(), w.error.c_str());
    mesh::Tileset back;
    std::string error;
    QVERIFY2(mesh::readTileset(path, back, error), error.c_str());
    QCOMPARE(back.tiles.size(), size_t(3));
    // Coarsest first, each the child of the one before, with its error.
    QCOMPARE(back.tiles[0].indices.size() / 3, asset.lods[1].triangles);
    QCOMPARE(back.tiles[1].indices.size() / 3, asset.lods[0].triangles);
    QCOMPARE(back.tiles[2].indices.size() / 3, asset.data->triangleCount());
    QCOMPARE(back.tiles[1].parent, 0);
    QCOMPARE(back.tiles[2].parent, 1);
    QCOMPARE(back.tiles[0].geometricError, asset.lods[1].hausdorff);
    QCOMPARE(back.tiles[2].geometricError, 0.0);
  }

  void roundTripThroughEcefByCli() {
    // A tileset at Meteora (ENU frame, as the import suite writes it) into a
    // scene in UTM, out again as ECEF 3D Tiles, into a second scene.
    const std::string d = dir("meteora");
    const auto bumps = [](double e, double n) { return 4.0 * std::sin(e / 30.0) * std::cos(n / 40.0); };
    const test::TestGrid grid = test::testGrid(-100, 100, -100, 100, 16, bumps);
    test::writeBytes(d + "/g.glb", test::glbOf(grid));
    const Json tileset = {{"asset", {{"version", "1.0"}}}, {"geometricError", 10},
                          {"root", {{"transform", test::matrixJson(test::enuToEcef(kLon, kLat, kHeight))},
                                    {"boundingVolume", {{"sphere", {0, 0, 0, 200}}}}, {"geometricError", 0},
                                    {"refine", "REPLACE"}, {"content", {{"uri", "g.glb"}}}}}};
    test::writeText(d + "/tileset.json", tileset.dump());
    const QString first = tmp_.path() + "/first.hscene", second = tmp_.path() + "/second.hscene";
    const QString out = QString::fromStdString(dir("out") + "/tileset.json");
    QCOMPARE(test::runCli({"new", first}, tmp_.path()).code, 0);
    QCOMPARE(test::runCli({"new", second}, tmp_.path()).code, 0);
    test::CliRun c = test::runCli({"import", QString::fromStdString(d + "/tileset.json"), first, "--name", "Pillar"},
                                  tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    c = test::runCli({"mesh", "export", first, "Pillar", out}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("3dtiles") && c.out.contains("EPSG:32634"), qPrintable(c.out));
    c = test::runCli({"import", out, second, "--name", "Back"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    // Both scenes' assets where each other's are: the first's origin and
    // the second's, in UTM, within a millimetre (the exported tiles went
    // through ECEF and an east-north-up frame and back).
    auto origin = [&](const QString& scene) {
      const test::CliRun i = test::runCli({"info", scene, "--json"}, tmp_.path());
      const Json info = Json::parse(i.out.toStdString());
      const Json& g = info.at("assets").at(0).at("origin");
      return glm::dvec3(g[0].get<double>(), g[1].get<double>(), g[2].get<double>());
    };
    const glm::dvec3 a = origin(first), b = origin(second);
    QVERIFY2(glm::length(a - b) < 1e-3, qPrintable(QString("origins %1 m apart").arg(glm::length(a - b))));
    QVERIFY(a.x > 100000.0 && a.y > 4000000.0);  // UTM metres, not ECEF
    // Draco through the CLI: said with its measured error, read back.
    const QString packed = QString::fromStdString(dir("packed") + "/tileset.json"), third = tmp_.path() + "/third.hscene";
    c = test::runCli({"mesh", "export", first, "Pillar", packed, "--draco-bits", "20"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("Draco: positions on a 20-bit grid, the largest move"), qPrintable(c.out));
    QCOMPARE(test::runCli({"new", third}, tmp_.path()).code, 0);
    c = test::runCli({"import", packed, third, "--name", "Packed"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    // 20 bits over a 283 m tile: a 0.27 mm grid.
    QVERIFY2(glm::length(origin(third) - a) < 1e-3, qPrintable(QString("%1 m").arg(glm::length(origin(third) - a))));
    c = test::runCli({"mesh", "export", first, "Pillar", packed, "--draco-bits", "5"}, tmp_.path());
    QVERIFY(c.code != 0);
    QVERIFY2(c.err.contains("8 to 30"), qPrintable(c.err));
  }
};

QTEST_GUILESS_MAIN(TestTilesetExport)
#include "test_tileset_export.moc"
