// Heightfield layout, queries, picking, bounds, CDLOD min/max tree and tile
// serialization.
#include <QtTest>

#include <cmath>
#include <random>

#include "terrain/heightfield.h"
#include "terrain/minmax_tree.h"
#include "terrain/ray_pick.h"
#include "terrain/terrain.h"
#include "terrain/tile_blob.h"

using namespace hs::terrain;

namespace {

Heightfield make(int n, double size, float h0 = 0.0f, glm::dvec3 origin = {}) {
  HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {size, size};
  d.origin = origin;
  d.initialHeight = h0;
  auto r = Heightfield::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  return r.take();
}

}  // namespace

class TestHeightfield : public QObject {
  Q_OBJECT
 private slots:
  void rejectsBadDescriptions() {
    HeightfieldDesc d;
    d.samplesX = 1;
    QVERIFY(!Heightfield::create(d));
    d.samplesX = 8194;
    QVERIFY(!Heightfield::create(d));
    d.samplesX = 100;
    d.sizeMetres = {0.0, 10.0};
    QVERIFY(!Heightfield::create(d));
    d.sizeMetres = {NAN, 10.0};
    QVERIFY(!Heightfield::create(d));
    d.sizeMetres = {10.0, 10.0};
    d.origin.x = INFINITY;
    auto r = Heightfield::create(d);
    QVERIFY(!r);
    QVERIFY(r.error().find("origin") != std::string::npos);
  }

  void tileLayout() {
    // 8193 = 64 * 128 + 1: 65 x 65 tiles, the last column one sample wide.
    Heightfield hf = make(8193, 8192.0);
    QCOMPARE(hf.heights().tilesX(), 65);
    QCOMPARE(hf.heights().tileCount(), 65 * 65);
    QCOMPARE(hf.spacing().x, 1.0);
    QCOMPARE(hf.heights().tileRegion(64).width(), 1);
    hf.set(8192, 8192, 5.0f);
    QCOMPARE(hf.at(8192, 8192), 5.0f);
    QCOMPARE(hf.range().max, 5.0f);
  }

  void bilinearAndNormals() {
    // A plane z = 0.5 x + 0.25 y over a 10 m grid with 65 samples.
    Heightfield hf = make(65, 640.0, 0.0f, {1000.0, 2000.0, 100.0});
    for (int y = 0; y < 65; ++y)
      for (int x = 0; x < 65; ++x) hf.heights().set(x, y, float(0.5 * x * 10.0 + 0.25 * y * 10.0));
    hf.updateAllBounds();
    QVERIFY(std::abs(hf.heightAtLocal({123.4, 456.7}) - float(0.5 * 123.4 + 0.25 * 456.7)) < 1e-3f);
    const glm::vec3 n = hf.normalAtLocal({300.0, 300.0});
    const glm::vec3 expect = glm::normalize(glm::vec3(-0.5f, -0.25f, 1.0f));
    QVERIFY(glm::length(n - expect) < 1e-5f);
    const auto s = hf.surfaceAtWorld({1000.0 + 100.0, 2000.0 + 200.0});
    QVERIFY(s.has_value());
    QVERIFY(std::abs(*s - (100.0 + 50.0 + 50.0)) < 1e-3);
    QVERIFY(!hf.surfaceAtWorld({999.0, 2000.0}).has_value());  // outside
    hf.setHole(10, 20, true);
    QVERIFY(!hf.surfaceAtWorld({1000.0 + 95.0, 2000.0 + 195.0}).has_value());  // cell (9,19) touches the hole
    QVERIFY(hf.surfaceAtWorld({1000.0 + 125.0, 2000.0 + 225.0}).has_value());
  }

  void rayPicking() {
    Heightfield hf = make(513, 512.0, 0.0f, {500000.0, 4400000.0, 0.0});  // UTM-sized origin
    // A bump in the middle.
    for (int y = 0; y < 513; ++y)
      for (int x = 0; x < 513; ++x) {
        const double r = std::hypot(x - 256.0, y - 256.0);
        hf.heights().set(x, y, float(50.0 * std::exp(-r * r / 2000.0)));
      }
    hf.updateAllBounds();
    // Straight down onto the top.
    auto hit = intersectRay(hf, {500256.0, 4400256.0, 1000.0}, {0, 0, -1});
    QVERIFY(hit.has_value());
    QVERIFY(std::abs(hit->world.z - 50.0) < 1e-3);
    QVERIFY(std::abs(hit->local.x - 256.0) < 1e-6);
    // Oblique, from far outside: the hit lies on the surface.
    const glm::dvec3 o(500000.0 - 300.0, 4400000.0 - 200.0, 300.0);
    const glm::dvec3 target(500300.0, 4400280.0, double(hf.heightAtLocal({300.0, 280.0})));
    hit = intersectRay(hf, o, target - o);
    QVERIFY(hit.has_value());
    const auto surf = hf.surfaceAtWorld(glm::dvec2(hit->world));
    QVERIFY(surf.has_value());
    QVERIFY2(std::abs(*surf - hit->world.z) < 1e-3, qPrintable(QString::number(*surf - hit->world.z)));
    // Aimed at the target, it must not stop early by more than the bump allows.
    QVERIFY(hit->distance <= glm::length(target - o) + 1e-3);
    // Missing the terrain.
    QVERIFY(!intersectRay(hf, {500256.0, 4400256.0, 1000.0}, {0, 0, 1}).has_value());
    QVERIFY(!intersectRay(hf, {400000.0, 4400256.0, 1000.0}, {0, 0, -1}).has_value());
    QVERIFY(!intersectRay(hf, o, {NAN, 0, 0}).has_value());
    // A hole lets the ray through.
    for (int y = 250; y <= 262; ++y)
      for (int x = 250; x <= 262; ++x) hf.setHole(x, y, true);
    QVERIFY(!intersectRay(hf, {500256.0, 4400256.0, 1000.0}, {0, 0, -1}).has_value());
  }

  void tileBoundsFollowEdits() {
    Heightfield hf = make(300, 299.0);
    hf.heights().set(128, 5, 7.0f);  // first column of tile 1: also bounds tile 0's cells
    hf.updateBounds({128, 5, 129, 6});
    QCOMPARE(hf.tileBounds(0).max, 7.0f);
    QCOMPARE(hf.tileBounds(1).max, 7.0f);
    QCOMPARE(hf.tileBounds(2).max, 0.0f);
    hf.heights().set(128, 5, 0.0f);
    hf.updateBounds({128, 5, 129, 6});
    QCOMPARE(hf.tileBounds(0).max, 0.0f);
  }

  void minMaxTree() {
    Heightfield hf = make(257, 256.0);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-10.f, 10.f);
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) hf.heights().set(x, y, u(rng));
    hf.updateAllBounds();
    MinMaxTree tree(hf, 32);
    QCOMPARE(tree.nodesX(0), 8);
    QCOMPARE(tree.levels(), 4);  // 8, 4, 2, 1
    auto brute = [&](int lv, int nx, int ny) {
      const int c = tree.nodeCells(lv);
      HeightRange r{1e9f, -1e9f};
      for (int y = ny * c; y <= std::min(ny * c + c, 256); ++y)
        for (int x = nx * c; x <= std::min(nx * c + c, 256); ++x) {
          r.min = std::min(r.min, hf.at(x, y));
          r.max = std::max(r.max, hf.at(x, y));
        }
      return r;
    };
    for (int lv = 0; lv < tree.levels(); ++lv)
      for (int ny = 0; ny < tree.nodesY(lv); ++ny)
        for (int nx = 0; nx < tree.nodesX(lv); ++nx) {
          const HeightRange a = tree.node(lv, nx, ny), b = brute(lv, nx, ny);
          QCOMPARE(a.min, b.min);
          QCOMPARE(a.max, b.max);
        }
    // Incremental update after an edit on a node edge.
    hf.heights().set(64, 64, 100.0f);
    const size_t n = tree.update(hf, {64, 64, 65, 65});
    QVERIFY(n < 16);
    QCOMPARE(tree.node(0, 1, 1).max, 100.0f);
    QCOMPARE(tree.node(0, 2, 2).max, 100.0f);
    QCOMPARE(tree.node(0, 1, 2).max, 100.0f);
    QCOMPARE(tree.node(3, 0, 0).max, 100.0f);
  }

  void tileBlobRoundTrip() {
    auto t = Terrain::create(HeightfieldDesc{300, 300, {299.0, 299.0}, {}, 3.0f, {}});
    QVERIFY(t.ok());
    Terrain& a = *t;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 500.f);
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 300; ++x) a.height.heights().set(x, y, y < 128 ? u(rng) : float(x) * 0.01f);
    a.height.updateAllBounds();
    a.height.setHole(3, 4, true);
    a.paint.blend(10, 10, 2, 0.4f);
    const TerrainRevisions saved = currentRevisions(a);

    auto b = Terrain::create(HeightfieldDesc{300, 300, {299.0, 299.0}, {}, 0.0f, {}});
    QVERIFY(b.ok());
    size_t bytes = 0;
    for (int tile = 0; tile < a.height.heights().tileCount(); ++tile) {
      auto blob = encodeHeightTile(a.height, tile);
      bytes += blob.size();
      QVERIFY(decodeTile(*b, blob).ok());
      QVERIFY(decodeTile(*b, encodeHolesTile(a.height, tile)).ok());
      for (int l = 0; l < a.paint.layerCount(); ++l) QVERIFY(decodeTile(*b, encodePaintTile(a.paint, l, tile)).ok());
    }
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 300; ++x) {
        QCOMPARE(b->height.at(x, y), a.height.at(x, y));
        QCOMPARE(b->height.isHole(x, y), a.height.isHole(x, y));
        for (int l = 0; l < a.paint.layerCount(); ++l) QCOMPARE(b->paint.raw(l, x, y), a.paint.raw(l, x, y));
      }
    QCOMPARE(b->height.range().max, a.height.range().max);
    qInfo("9 height tiles (300^2 samples, one third noise) encode to %zu bytes (raw %zu)", bytes,
          size_t(9) * TileGrid<float>::tileBytes());

    // Damage is detected and named.
    auto blob = encodeHeightTile(a.height, 0);
    blob[blob.size() / 2] ^= 0x55;
    Status s = decodeTile(*b, blob);
    QVERIFY(!s.ok());
    QVERIFY(s.error.find("tile 0") != std::string::npos);
    blob.resize(10);
    QVERIFY(!decodeTile(*b, blob).ok());
    QVERIFY(!decodeTile(*b, {}).ok());

    // Dirty tracking: only the tile that changed after the save.
    a.height.heights().set(200, 200, 1.0f);
    const DirtyTiles dirty = tilesChangedSince(a, saved);
    QCOMPARE(dirty.heights.size(), size_t(1));
    QCOMPARE(dirty.heights[0], a.height.heights().tileIndex(200, 200));
    QCOMPARE(dirty.holes.size(), size_t(0));
    QCOMPARE(dirty.paint.size(), size_t(0));
    QCOMPARE(tileBlobKey(TileKind::Paint, 2, 1, 3), std::string("paint/2/1_3"));
  }
};

QTEST_GUILESS_MAIN(TestHeightfield)
#include "test_terrain_heightfield.moc"
