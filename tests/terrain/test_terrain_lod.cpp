// LodErrorMap (the CDLOD renderer's per-level geometric error): against a
// brute-force evaluation at every sample, on grids that are and are not a
// multiple of the tile size, before and after edits (incremental update),
// and monotone in the level.
#include <QtTest>

#include <random>

#include "terrain/lod_error.h"
#include "terrain/noise.h"

using namespace hs::terrain;

namespace {

Heightfield hills(int nx, int ny, uint64_t seed) {
  HeightfieldDesc d;
  d.samplesX = nx;
  d.samplesY = ny;
  d.sizeMetres = glm::dvec2(nx - 1, ny - 1);
  Heightfield hf = Heightfield::create(d).take();
  FractalNoise n;
  n.seed = seed;
  n.scale = 40.0;
  n.octaves = 6;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) hf.set(x, y, 30.0f * n.at(x, y));
  hf.updateAllBounds();
  return hf;
}

float bruteForce(const Heightfield& hf, int level) {
  float e = 0.0f;
  for (int y = 0; y < hf.samplesY(); ++y)
    for (int x = 0; x < hf.samplesX(); ++x) e = std::max(e, lodErrorAt(hf, level, x, y));
  return e;
}

}  // namespace

class TestTerrainLod : public QObject {
  Q_OBJECT
 private slots:
  void matchesBruteForce_data() {
    QTest::addColumn<int>("nx");
    QTest::addColumn<int>("ny");
    QTest::newRow("257 (tiles + 1)") << 257 << 257;
    QTest::newRow("300 x 190 (ragged)") << 300 << 190;
    QTest::newRow("1025 x 33") << 1025 << 33;
  }
  void matchesBruteForce() {
    QFETCH(int, nx);
    QFETCH(int, ny);
    Heightfield hf = hills(nx, ny, 3);
    const int levels = 9;
    LodErrorMap m(hf, levels);
    QCOMPARE(m.levels(), levels);
    QCOMPARE(m.error(0), 0.0f);
    float previous = 0.0f;
    for (int l = 1; l < levels; ++l) {
      float brute = 0.0f;
      for (int k = 1; k <= l; ++k) brute = std::max(brute, bruteForce(hf, k));  // monotone envelope
      QVERIFY2(std::abs(m.error(l) - brute) <= 1e-4f * std::max(1.0f, brute),
               qPrintable(QString("level %1: %2 vs %3").arg(l).arg(m.error(l)).arg(brute)));
      QVERIFY(m.error(l) >= previous);
      previous = m.error(l);
    }
    QVERIFY(m.error(levels - 1) > 1.0f);  // hills: coarse levels are far off
  }

  void incrementalUpdateEqualsRebuild() {
    Heightfield hf = hills(513, 513, 9);
    LodErrorMap m(hf, 8);
    std::mt19937 rng(1);
    for (int k = 0; k < 20; ++k) {
      // A spike or a pit somewhere (edges and tile corners included).
      const int x = int(rng() % 513), y = int(rng() % 513);
      const float h = float(int(rng() % 200)) - 100.0f;
      hf.set(x, y, h);
      const Region r{x, y, x + 1, y + 1};
      hf.updateBounds(r);
      m.update(hf, r);
    }
    const LodErrorMap fresh(hf, 8);
    for (int l = 0; l < 8; ++l) QCOMPARE(m.error(l), fresh.error(l));
    // A flat terrain has no error at any level.
    HeightfieldDesc d;
    d.samplesX = d.samplesY = 129;
    d.initialHeight = 12.0f;
    const Heightfield flat = Heightfield::create(d).take();
    const LodErrorMap f(flat, 6);
    for (int l = 0; l < 6; ++l) QCOMPARE(f.error(l), 0.0f);
  }
};

QTEST_GUILESS_MAIN(TestTerrainLod)
#include "test_terrain_lod.moc"
