// Ambient occlusion against a CPU ray cast (tests/common/ao_reference.h):
// GTAO's visibility on a small scene (a floor, two spheres, a wall) within
// a tolerance of the ray-cast visibility of the same depth buffer, closer
// to it than the plain SSAO, and open floor left open.
#include <QtTest>

#include "ao_reference.h"

using namespace hs;

class TestAoRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void gtaoMatchesARayCast() {
    const test::AoScene sc = test::aoScene(200, 150);
    const float radius = 1.0f;
    const test::RenderedAo gtao = test::renderAo(r_, sc, scene::AmbientOcclusion::Gtao, radius);
    const test::RenderedAo ssao = test::renderAo(r_, sc, scene::AmbientOcclusion::Ssao, radius);
    const std::vector<float> reference = test::rayCastAo(sc, gtao.depth, radius, 144);
    const test::AoError g = test::compareAo(gtao.visibility, reference);
    const test::AoError s = test::compareAo(ssao.visibility, reference);
    qInfo("GTAO: mean error %.4f, 95th percentile %.4f, bias %+.4f; SSAO: %.4f, %.4f, %+.4f; %zu pixels, %.0f%% "
          "occluded below 0.9",
          g.mean, g.p95, g.bias, s.mean, s.p95, s.bias, g.pixels, 100.0 * g.occludedShare);
    QVERIFY(g.pixels > 200 * 150 / 2);
    QVERIFY2(g.occludedShare > 0.1, "the scene must have occluded pixels to measure");
    // Measured: mean 0.028, 95th percentile 0.139 (SSAO 0.038, 0.170).
    QVERIFY2(g.mean < 0.04, qPrintable(QString("GTAO mean error %1").arg(g.mean)));
    QVERIFY2(g.p95 < 0.18, qPrintable(QString("GTAO 95th percentile %1").arg(g.p95)));
    QVERIFY2(g.mean < s.mean, qPrintable(QString("GTAO %1, SSAO %2").arg(g.mean).arg(s.mean)));
    // Open floor (the ray cast sees no occluder) stays open.
    double openSum = 0.0;
    int open = 0;
    for (size_t i = 0; i < reference.size(); ++i)
      if (reference[i] == 1.0f && gtao.visibility[i] >= 0.0f) {
        openSum += double(gtao.visibility[i]);
        ++open;
      }
    QVERIFY(open > 1000);
    QVERIFY2(openSum / open > 0.98, qPrintable(QString("open floor %1").arg(openSum / open)));
  }
};

QTEST_GUILESS_MAIN(TestAoRender)
#include "test_ao_render.moc"
