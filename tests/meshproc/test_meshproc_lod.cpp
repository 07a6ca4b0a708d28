// LOD chains and the screen-space selection rule.
#include <QtTest>

#include <cmath>

#include "meshproc/lod_chain.h"
#include "mesh_builders.h"

using namespace hs::mesh;

class TestMeshprocLod : public QObject {
  Q_OBJECT

 private slots:
  void chainShrinksByRatioWithGrowingError() {
    const MeshData base = hs::test::icosphere(5, 10.0);  // 20480 faces, radius 10 m
    LodOptions o;
    o.levels = 3;
    o.ratio = 0.25;
    const LodChain c = buildLodChain(base, o);
    QVERIFY2(c.error.empty(), c.error.c_str());
    QCOMPARE(c.levels.size(), size_t(4));
    QCOMPARE(c.levels[0].hausdorff, 0.0);
    for (size_t i = 1; i < c.levels.size(); ++i) {
      const double want = double(c.levels[i - 1].triangles) * 0.25;
      QVERIFY(std::abs(double(c.levels[i].triangles) - want) <= 2.0);
      QVERIFY(c.levels[i].hausdorff > c.levels[i - 1].hausdorff);
      QVERIFY(c.levels[i].hausdorffRel > 0 && c.levels[i].hausdorffRel < 0.05);
      QVERIFY(c.levels[i].mesh.textures.empty());  // levels share level 0's textures
    }
  }

  void chainStopsAtTheMinimumSize() {
    LodOptions o;
    o.levels = 10;
    o.minTriangles = 100;
    const LodChain c = buildLodChain(hs::test::icosphere(3, 1.0), o);  // 1280 faces
    QCOMPARE(c.levels.size(), size_t(2));  // 1280, 320; the next (80) would be under 100
  }

  void selectionPicksTheCoarsestLevelUnderOnePixel() {
    const std::vector<double> errors = {0.0, 0.01, 0.04, 0.16};  // metres
    const double fov = 60.0 * M_PI / 180.0, height = 1080.0;
    // One pixel at distance d is 2 d tan(30 deg) / 1080 metres.
    auto pixel = [&](double d) { return 2.0 * d * std::tan(fov / 2) / height; };
    QCOMPARE(projectedErrorPixels(pixel(100.0), 100.0, fov, height), 1.0);
    QCOMPARE(selectLod(errors, 1.0, fov, height), 0);
    // Level 1's 1 cm is one pixel at ~9.35 m.
    const double d1 = 0.01 / pixel(1.0);
    QCOMPARE(selectLod(errors, d1 * 0.99, fov, height), 0);
    QCOMPARE(selectLod(errors, d1 * 1.01, fov, height), 1);
    QCOMPARE(selectLod(errors, 1e6, fov, height), 3);
    QCOMPARE(selectLod(errors, d1 * 1.01 * 2, fov, height, 2.0), 2);  // a 2-pixel budget
    QCOMPARE(selectLod(errors, 0.0, fov, height), 0);
    QCOMPARE(selectLod({}, 10.0, fov, height), 0);
    // lodDistance inverts projectedErrorPixels: d1 for one pixel, twice d1 for half a pixel.
    QVERIFY(std::abs(lodDistance(0.01, fov, height, 1.0) / d1 - 1.0) < 1e-12);
    QVERIFY(std::abs(lodDistance(0.01, fov, height, 0.5) / (2.0 * d1) - 1.0) < 1e-12);
    QVERIFY(std::abs(projectedErrorPixels(0.04, lodDistance(0.04, fov, height, 3.0), fov, height) - 3.0) < 1e-12);
    QVERIFY(std::isinf(lodDistance(0.01, fov, height, 0.0)));  // no bound: never coarser
    QVERIFY(std::isinf(lodDistance(0.01, 0.0, height, 1.0)));
    QVERIFY(std::isinf(lodDistance(0.01, fov, height, std::nan(""))));
  }

  void cancelStopsTheChain() {
    hs::Progress p;
    p.cancel();
    LodOptions o;
    const LodChain c = buildLodChain(hs::test::icosphere(4, 1.0), o, &p);
    QVERIFY(c.cancelled);
  }
};

QTEST_GUILESS_MAIN(TestMeshprocLod)
#include "test_meshproc_lod.moc"
