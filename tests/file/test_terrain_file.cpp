// Terrain tiles in the .hscene file: bit-exact round trips (heights, holes,
// paint weights, spacing, origin, CRS), a save after one brush stroke that
// writes only the touched tiles (measured on an 8193^2 terrain), saves from
// a snapshot while the live terrain changes, and every kind of damaged or
// missing tile reported with the terrain's and the tile's name.
#include <QtTest>

#include <chrono>
#include <filesystem>
#include <random>

#include "hscene_sql.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/scene_json.h"
#include "scene/terrain_edits.h"
#include "scene/terrain_file.h"
#include "scene/terrain_layer_ops.h"
#include "scene/terrain_ops.h"
#include "terrain/stroke.h"
#include "terrain/tile_blob.h"
#include "terrain_compare.h"
#include "truncation.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;
using hs::test::sql;

namespace {

EntityId makeTerrain(Document& doc, int samples, double size, const std::string& name, bool hills = true) {
  ops::NewTerrain spec;
  spec.name = name;
  spec.samplesX = spec.samplesY = samples;
  spec.sizeMetres = glm::dvec2(size);
  spec.start = hills ? ops::NewTerrain::Start::Hills : ops::NewTerrain::Start::Flat;
  spec.heightRange = {10.0f, 60.0f};
  std::string error;
  const EntityId id = ops::addTerrain(doc, spec, error);
  if (id == kNoEntity) qFatal("addTerrain: %s", error.c_str());
  return id;
}

TerrainData& data(Document& doc, EntityId e) { return *terrainOf(doc.state(), e)->data; }

void dab(Document& doc, EntityId e, terrain::BrushTool tool, glm::dvec2 local, double radius, int layer = 2) {
  TerrainData& d = data(doc, e);
  terrain::BrushSettings s;
  s.tool = tool;
  s.radius = radius;
  s.strength = tool == terrain::BrushTool::Raise ? 3.0f : 1.0f;
  s.paintLayer = layer;
  terrain::Stroke st(d.terrain(), s);
  const terrain::StrokeUpdate u = st.dabAt(local);
  noteTerrainChange(doc, doc.state().find(e)->terrain->terrain, d, u.changed, changeKindsOf(tool));
  pushTerrainStep(doc, doc.state().find(e)->terrain->terrain, st.finish(), "dab");
}

int tileCount(const std::string& path) { return test::countBlobKeys(path, "key LIKE 'terrain/%'"); }

}  // namespace

class TestTerrainFile : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const std::string& name) const { return tmp_.filePath(QString::fromStdString(name)).toStdString(); }

  // A scene with two terrains: one with hills, paint, holes and a CRS.
  void richScene(Document& doc) {
    const EntityId a = makeTerrain(doc, 300, 299.0, "Valley");  // not a multiple of the tile size
    makeTerrain(doc, 65, 64.0, "Small", false);
    dab(doc, a, terrain::BrushTool::Paint, {100.0, 120.0}, 40.0, 2);
    dab(doc, a, terrain::BrushTool::Paint, {180.0, 60.0}, 25.0, 5);
    dab(doc, a, terrain::BrushTool::Holes, {150.0, 150.0}, 6.0);
    terrain::GeoReference geo;
    geo.crsWkt = "PROJCS[\"test\"]";
    geo.crsName = "test CRS";
    geo.epsg = 32634;
    data(doc, a).terrain().height.setGeo(geo);
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void roundTripIsBitExact() {
    Document doc;
    richScene(doc);
    const std::string p = path("rich.hscene");
    std::string error;
    SaveReport r;
    QVERIFY2(saveScene(doc.state(), p, error, &r), error.c_str());
    // Heights: every tile; holes and paint: only tiles that hold something.
    const auto& big = data(doc, doc.state().findByName("Valley")).terrain();
    QVERIFY(r.tilesWritten > size_t(big.height.heights().tileCount()) + 1);
    QCOMPARE(int(r.tilesWritten), tileCount(p));
    std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(canonicalJson(*back), canonicalJson(doc.state()));
    for (const auto& [id, t] : doc.state().terrains) {
      const TerrainAsset* b = back->findTerrain(id);
      QVERIFY(b);
      const std::string diff = test::terrainDifference(b->data->terrain(), t.data->terrain());
      QVERIFY2(diff.empty(), diff.c_str());
      QCOMPARE(b->data->heights().geo().crsWkt, t.data->heights().geo().crsWkt);
      QCOMPARE(b->data->heights().range().max, t.data->heights().range().max);  // bounds rebuilt
    }
    // Saving the loaded scene back writes no tile.
    SaveReport again;
    QVERIFY2(saveScene(*back, p, error, &again), error.c_str());
    QCOMPARE(again.tilesWritten, size_t(0));
    QCOMPARE(again.tilesRemoved, size_t(0));
  }

  // DESIGN.md: a save after one brush stroke on an 8k terrain writes a few tiles.
  void saveAfterOneStrokeOn8kWritesOnlyItsTiles() {
    Document doc;
    const EntityId e = makeTerrain(doc, 8193, 8192.0, "Big", false);
    const std::string p = path("big.hscene");
    std::string error;
    SaveReport first;
    auto t0 = std::chrono::steady_clock::now();
    QVERIFY2(saveScene(doc.state(), p, error, &first), error.c_str());
    const double firstS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    QCOMPARE(first.tilesWritten, size_t(65 * 65));
    doc.markSaved();
    // One stroke of radius 100 m (samples) across a tile corner.
    dab(doc, e, terrain::BrushTool::Raise, {4096.0, 4096.0}, 100.0);
    SaveReport second;
    t0 = std::chrono::steady_clock::now();
    QVERIFY2(saveScene(snapshotForSave(doc.state()), p, error, &second), error.c_str());
    const double secondS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    qInfo("8193^2 flat terrain: first save %zu tiles, %.1f KiB in %.3f s; after one radius-100 stroke: %zu tiles, %.1f KiB "
          "in %.3f s (%zu unchanged)",
          first.tilesWritten, double(first.tileBytesWritten) / 1024.0, firstS, second.tilesWritten,
          double(second.tileBytesWritten) / 1024.0, secondS, second.tilesUnchanged);
    QVERIFY(second.incremental);
    QCOMPARE(second.tilesWritten, size_t(4));  // the stroke covers the four tiles around the corner
    QCOMPARE(second.tilesUnchanged, size_t(65 * 65 - 4));
    QVERIFY(second.tileBytesWritten < 300 * 1024);
    // Undo back to the saved state: the next save writes the four back.
    doc.undoStack()->undo();
    SaveReport third;
    QVERIFY2(saveScene(doc.state(), p, error, &third), error.c_str());
    QCOMPARE(third.tilesWritten, size_t(4));
    std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(canonicalJson(*back), canonicalJson(doc.state()));
  }

  // A save from a snapshot holds the state of the moment it was taken,
  // however the live terrain changes while it is written.
  void snapshotSaveIsUnaffectedByLaterEdits() {
    Document doc;
    const EntityId e = makeTerrain(doc, 257, 256.0, "Live");
    const SceneState snap = snapshotForSave(doc.state());
    const terrain::Terrain at = data(doc, e).terrain().clone();
    dab(doc, e, terrain::BrushTool::Raise, {128.0, 128.0}, 60.0);
    dab(doc, e, terrain::BrushTool::Holes, {30.0, 30.0}, 10.0);
    const std::string p = path("snap.hscene");
    std::string error;
    QVERIFY2(saveScene(snap, p, error), error.c_str());
    std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    const std::string diff = test::terrainDifference(back->terrains.begin()->second.data->terrain(), at);
    QVERIFY2(diff.empty(), diff.c_str());
  }

  // ---- damage ---------------------------------------------------------------
  void damagedTileNamesTerrainAndTile() {
    Document doc;
    richScene(doc);
    const std::string good = path("good.hscene");
    std::string error;
    QVERIFY2(saveScene(doc.state(), good, error), error.c_str());
    struct Case {
      const char* name;
      std::string statement;
      std::vector<std::string> expect;
    };
    const std::vector<Case> cases = {
        {"flipped byte", "UPDATE blobs SET data = substr(data, 1, 60) || x'00' || substr(data, 62) WHERE key = 'terrain/1/h/1_1'",
         {"terrain 'Valley' (id 1)", "height tile 1_1", "damaged"}},
        {"truncated", "UPDATE blobs SET data = substr(data, 1, 20) WHERE key = 'terrain/1/h/2_0'",
         {"terrain 'Valley'", "height tile 2_0", "damaged"}},
        {"missing height tile", "DELETE FROM blobs WHERE key = 'terrain/1/h/0_2'",
         {"terrain 'Valley'", "height tile 0_2", "missing"}},
        {"missing paint tile", "DELETE FROM blobs WHERE key LIKE 'terrain/1/paint/5/%'",
         {"terrain 'Valley'", "paint layer 5 tile", "missing"}},
        {"missing holes tile", "DELETE FROM blobs WHERE key LIKE 'terrain/1/holes/%'",
         {"terrain 'Valley'", "holes tile 1_1", "missing"}},
        {"tile under another key", "UPDATE blobs SET data = (SELECT data FROM blobs WHERE key = 'terrain/1/h/0_0') "
                                   "WHERE key = 'terrain/1/h/1_0'",
         {"terrain 'Valley'", "height tile 1_0", "checksum"}},
        {"stray tile", "INSERT INTO blobs(key, part, hash, data) SELECT 'terrain/2/holes/0_0', 0, hash, data FROM blobs "
                       "WHERE key = 'terrain/1/holes/1_1'",
         {"terrain 'Small' (id 2)", "holes tile 0_0"}},
        {"foreign key", "INSERT INTO blobs(key, part, hash, data) VALUES ('terrain/1/h/99_0', 0, 'x', x'00')",
         {"terrain 'Valley'", "does not belong"}},
    };
    for (const Case& c : cases) {
      const std::string p = path(std::string("damaged_") + c.name + ".hscene");
      fs::copy_file(good, p, fs::copy_options::overwrite_existing);
      sql(p, c.statement);
      error.clear();
      QVERIFY2(!loadScene(p, error), c.name);
      for (const std::string& want : c.expect)
        QVERIFY2(error.find(want) != std::string::npos, qPrintable(QString("%1: '%2' not in: %3").arg(c.name, want.c_str(), error.c_str())));
      QVERIFY2(error.find(p) != std::string::npos, error.c_str());
    }
  }

  // Height, holes and paint tile blobs (deflated, each the largest of its
  // kind) cut at every length: an error naming the tile, and the terrain
  // it was decoded into unchanged.
  void tileBlobsCutAtEveryLength() {
    Document doc;
    richScene(doc);
    terrain::Terrain& t = data(doc, doc.state().findByName("Valley")).terrain();
    const int tiles = t.height.heights().tileCount();
    auto largest = [&](auto encode) {
      std::vector<uint8_t> best;
      for (int i = 0; i < tiles; ++i)
        if (std::vector<uint8_t> b = encode(i); b.size() > best.size()) best = std::move(b);
      return best;
    };
    const std::vector<std::vector<uint8_t>> blobs = {
        largest([&](int i) { return terrain::encodeHeightTile(t.height, i); }),
        largest([&](int i) { return terrain::encodeHolesTile(t.height, i); }),
        largest([&](int i) { return terrain::encodePaintTile(t.paint, 2, i); })};
    const terrain::Terrain before = t.clone();
    for (const std::vector<uint8_t>& blob : blobs) {
      QVERIFY2(blob.size() > 40, qPrintable(QString::number(blob.size())));  // a tile with content (a uniform one is 32 + 1 to 4 bytes)
      QVERIFY(terrain::decodeTile(t, blob).ok());
      for (size_t n : test::cutLengths(blob.size(), 1)) {
        const std::vector<uint8_t> cut(blob.begin(), blob.begin() + long(n));
        const terrain::Status s = terrain::decodeTile(t, cut);
        QVERIFY2(!s.ok(), qPrintable(QString("cut at %1 of %2 decoded").arg(n).arg(blob.size())));
        QVERIFY2(s.error.rfind("terrain tile", 0) == 0, s.error.c_str());
      }
    }
    const std::string diff = test::terrainDifference(t, before);
    QVERIFY2(diff.empty(), diff.c_str());
  }

  // A description from an older save next to newer tiles of the same
  // terrain (each tile fine on its own) is caught by the content summary.
  void staleDescriptionIsCaught() {
    Document doc;
    const EntityId e = makeTerrain(doc, 129, 128.0, "T");
    const std::string p = path("stale.hscene");
    std::string error;
    QVERIFY2(saveScene(doc.state(), p, error), error.c_str());
    const std::string oldCopy = path("stale_old.hscene");
    fs::copy_file(p, oldCopy, fs::copy_options::overwrite_existing);
    dab(doc, e, terrain::BrushTool::Raise, {64.0, 64.0}, 20.0);
    QVERIFY2(saveScene(doc.state(), p, error), error.c_str());
    // Put the old description into the new file.
    sql(p, "ATTACH DATABASE '" + oldCopy + "' AS old; UPDATE document SET json = (SELECT json FROM old.document)");
    QVERIFY(!loadScene(p, error));
    QVERIFY2(error.find("terrain 'T'") != std::string::npos && error.find("damaged") != std::string::npos, error.c_str());
  }

  // Adding and removing paint layers (the base layer included) saves and
  // reopens exactly, and the save drops the blobs of the layer that went.
  void layerEditsRoundTrip() {
    Document doc;
    const EntityId e = makeTerrain(doc, 200, 199.0, "Layers");
    const TerrainId tid = doc.state().find(e)->terrain->terrain;
    dab(doc, e, terrain::BrushTool::Paint, {60.0, 60.0}, 30.0, 2);
    dab(doc, e, terrain::BrushTool::Paint, {140.0, 140.0}, 30.0, 7);
    const std::string p = path("layers.hscene");
    std::string error;
    QVERIFY2(saveScene(doc.state(), p, error), error.c_str());
    QVERIFY2(ops::removeTerrainLayer(doc, tid, 0, error), error.c_str());  // the base layer
    QVERIFY2(ops::removeTerrainLayer(doc, tid, 6, error), error.c_str());  // was 7
    QVERIFY(ops::addTerrainLayer(doc, tid, terrain::Material{}, error) == 6);
    dab(doc, e, terrain::BrushTool::Paint, {100.0, 30.0}, 20.0, 6);
    SaveReport r;
    QVERIFY2(saveScene(doc.state(), p, error, &r), error.c_str());
    QVERIFY(r.tilesRemoved > 0);  // the old layer 7's tiles
    std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(canonicalJson(*back), canonicalJson(doc.state()));
    const std::string diff = test::terrainDifference(back->findTerrain(tid)->data->terrain(), data(doc, e).terrain());
    QVERIFY2(diff.empty(), diff.c_str());
    QCOMPARE(back->findTerrain(tid)->data->terrain().paint.layerCount(), 7);
  }
};

QTEST_GUILESS_MAIN(TestTerrainFile)
#include "test_terrain_file.moc"
