// Paint layers: weights sum to 1 after every operation; rules by altitude
// and slope; masks for other systems.
#include <QtTest>

#include <random>

#include "terrain/paint_rule_preview.h"
#include "terrain/paint_rules.h"
#include "terrain/stroke.h"
#include "terrain_compare.h"

using namespace hs::terrain;

namespace {

Terrain make(int n, double size) {
  HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {size, size};
  d.origin = {0.0, 0.0, 200.0};
  auto r = Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  return r.take();
}

}  // namespace

class TestPaint : public QObject {
  Q_OBJECT
 private slots:
  void defaults() {
    Terrain t = make(65, 64.0);
    QVERIFY(t.paint.layerCount() >= 8);
    QCOMPARE(t.paint.weight(0, 10, 10), 1.0f);
    QCOMPARE(t.paint.memoryBytes(), size_t(0));  // nothing painted, nothing stored
    QCOMPARE(t.paint.maxSumError(t.height.bounds()), 0.0);
    Material m = t.paint.material(2);
    QVERIFY(!m.name.empty());
    m.tilingMetres = -1.0f;
    QVERIFY(!t.paint.setMaterial(2, m).ok());
  }

  void blendArithmetic() {
    uint16_t q[8] = {65535, 0, 0, 0, 0, 0, 0, 0};
    blendWeights(q, 8, 3, 0.5f, 0);
    QCOMPARE(int(q[3]), 32768);
    QCOMPARE(int(q[0]), 65535 - 32768);
    blendWeights(q, 8, 5, 0.3f, 0);
    int sum = 0;
    for (uint16_t v : q) sum += v;
    QCOMPARE(sum, 65535);
    blendWeights(q, 8, 5, 1.0f, 0);  // full strength: only layer 5
    QCOMPARE(int(q[5]), 65535);
    blendWeights(q, 8, 5, -1.0f, 0);  // erase the only layer: weight goes to the fallback
    QCOMPARE(int(q[0]), 65535);
    QCOMPARE(int(q[5]), 0);
    blendWeights(q, 8, 2, NAN, 0);  // ignored
    QCOMPARE(int(q[0]), 65535);
  }

  void randomPaintingKeepsSumOne() {
    Terrain t = make(300, 299.0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> pos(0.0, 300.0), rad(2.0, 50.0);
    std::uniform_real_distribution<float> str(0.0f, 1.0f);
    std::uniform_int_distribution<int> layer(0, 7);
    for (int i = 0; i < 60; ++i) {
      BrushSettings s;
      s.tool = BrushTool::Paint;
      s.radius = rad(rng);
      s.strength = str(rng);
      s.paintLayer = layer(rng);
      s.erase = (rng() % 4) == 0;
      Stroke st(t, s, int(rng() % 2) + 1);
      for (int k = 0; k < 4; ++k) st.moveTo({pos(rng), pos(rng)}, str(rng));
      st.finish();
      QVERIFY(t.paint.maxSumError(t.height.bounds()) < 1e-6);
    }
    // Something was painted on several layers.
    int used = 0;
    for (int l = 1; l < 8; ++l) used += t.paint.grid(l).allocatedTiles() > 0;
    QVERIFY(used >= 5);
  }

  void rulesByAltitudeAndSlope() {
    Terrain t = make(201, 200.0);
    // West half: flat at 10 m (world 210); east half: a 45-degree ramp up.
    for (int y = 0; y < 201; ++y)
      for (int x = 0; x < 201; ++x) t.height.heights().set(x, y, x < 100 ? 10.0f : 10.0f + float(x - 100));
    t.height.updateAllBounds();
    PaintRule grass;
    grass.layer = 1;
    grass.useSlope = true;
    grass.slopeMin = 0.0;
    grass.slopeMax = 20.0;
    grass.slopeBlend = 5.0;
    PaintRule rock;
    rock.layer = 2;
    rock.useSlope = true;
    rock.slopeMin = 35.0;
    rock.slopeMax = 90.0;
    rock.slopeBlend = 5.0;
    PaintRule snow;
    snow.layer = 7;
    snow.useAltitude = true;
    snow.altitudeMin = 280.0;  // world metres: the top of the ramp
    snow.altitudeMax = 1e4;
    snow.altitudeBlend = 10.0;
    PaintRulesResult r = applyPaintRules(t, {grass, rock, snow});
    QVERIFY(r.ok());
    QVERIFY(t.paint.maxSumError(t.height.bounds()) < 1e-6);
    QCOMPARE(t.paint.weight(1, 50, 100), 1.0f);   // flat: grass
    QCOMPARE(t.paint.weight(2, 150, 100), 1.0f);  // 45 degrees: rock
    QCOMPARE(t.paint.weight(7, 195, 100), 1.0f);  // altitude 295 m: snow over rock
    QVERIFY(t.paint.weight(7, 160, 100) == 0.0f);
    // Blend band: 275 m world is 5 m below the snow line, inside the 10 m blend.
    const float partial = t.paint.weight(7, 165, 100);  // world 275 m: 5 m into the 10 m blend
    QVERIFY2(partial > 0.0f && partial < 1.0f, qPrintable(QString::number(partial)));
    QCOMPARE(ruleWeight(snow, 275.0, 0.0), 0.5f);
    // A rule naming a missing layer is skipped with a warning, not a crash.
    PaintRule bad;
    bad.layer = 99;
    PaintRulesResult r2 = applyPaintRules(t, {bad});
    QVERIFY(r2.ok());
    QCOMPARE(r2.warnings.size(), size_t(1));

    // Random rules on a random field, then random painting: still sum 1.
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.f, 80.f);
    for (int y = 0; y < 201; ++y)
      for (int x = 0; x < 201; ++x) t.height.heights().set(x, y, u(rng));
    t.height.updateAllBounds();
    std::vector<PaintRule> rules;
    std::uniform_real_distribution<double> a(150.0, 300.0), s(0.0, 80.0);
    for (int i = 0; i < 8; ++i) {
      PaintRule p;
      p.layer = i;
      p.useAltitude = i % 2 == 0;
      p.altitudeMin = a(rng);
      p.altitudeMax = p.altitudeMin + 30.0;
      p.useSlope = i % 3 != 0;
      p.slopeMin = s(rng);
      p.slopeMax = p.slopeMin + 20.0;
      p.strength = 0.7f;
      rules.push_back(p);
    }
    QVERIFY(applyPaintRules(t, rules).ok());
    QVERIFY(t.paint.maxSumError(t.height.bounds()) < 1e-6);
  }

  void layerMaskAndLayerEdits() {
    Terrain t = make(129, 128.0);
    BrushSettings s;
    s.tool = BrushTool::Paint;
    s.paintLayer = 4;
    s.radius = 20.0;
    s.strength = 1.0f;
    s.falloff.falloff = 0.0f;
    Stroke st(t, s);
    st.dabAt({64.0, 64.0});
    st.finish();
    auto mask = exportLayerMask(t.paint, 4);
    QVERIFY(mask.ok());
    QCOMPARE(mask->at(64, 64), 1.0f);
    QCOMPARE(mask->at(5, 5), 0.0f);
    QCOMPARE(t.paint.weightAt(4, {64.0, 64.0}), 1.0f);
    QVERIFY(!exportLayerMask(t.paint, 42).ok());
    // Removing a layer gives its weight to the others; sums stay 1.
    QVERIFY(t.paint.removeLayer(4).ok());
    QCOMPARE(t.paint.layerCount(), 7);
    QVERIFY(t.paint.maxSumError(t.height.bounds()) < 1e-6);
    QCOMPARE(t.paint.weight(0, 64, 64), 1.0f);
    auto added = t.paint.addLayer(Material{});
    QVERIFY(added.ok());
    QVERIFY(t.paint.maxSumError(t.height.bounds()) < 1e-6);
    while (t.paint.layerCount() < kMaxPaintLayers) QVERIFY(t.paint.addLayer(Material{}).ok());
    QVERIFY(!t.paint.addLayer(Material{}).ok());
  }

  // Removing the base layer: its weight goes to the others, and the new
  // base layer reads 1 where nothing is stored (what files and the renderer
  // assume of layer 0). Removing a layer painted in one corner touches only
  // that corner's tiles.
  void removingTheBaseLayer() {
    Terrain t = make(300, 299.0);
    BrushSettings s;
    s.tool = BrushTool::Paint;
    s.paintLayer = 3;
    s.radius = 30.0;
    s.strength = 0.6f;
    Stroke st(t, s);
    st.dabAt({40.0, 40.0});
    st.finish();
    const float before3 = t.paint.weight(3, 40, 40);
    QVERIFY(before3 > 0.5f && before3 < 1.0f);
    QVERIFY(t.paint.removeLayer(0).ok());
    QCOMPARE(t.paint.layerCount(), 7);
    QCOMPARE(t.paint.grid(0).fill(), kWeightOne);
    QCOMPARE(hs::test::paintSumError(t.paint), 0L);  // the 16-bit weights sum to exactly 65535
    QCOMPARE(t.paint.weight(2, 40, 40), 1.0f);        // old layer 3 had all the rest there
    QCOMPARE(t.paint.weight(0, 250, 250), 1.0f);      // far away: the new base layer
    QCOMPARE(t.paint.grid(0).allocatedTiles(), size_t(1));  // only the painted tile is stored
    QVERIFY(t.paint.removeLayer(2).ok());              // the painted one: back to the base layer
    QCOMPARE(t.paint.weight(0, 40, 40), 1.0f);
    QCOMPARE(t.paint.memoryBytes(), size_t(0));
  }

  // The rules editor's preview reads the samples applyPaintRules reads.
  void rulePreviewMatchesTheRule() {
    Terrain t = make(201, 200.0);
    for (int y = 0; y < 201; ++y)
      for (int x = 0; x < 201; ++x) t.height.heights().set(x, y, x < 100 ? 10.0f : 10.0f + float(x - 100));
    t.height.updateAllBounds();
    PaintRule rock;
    rock.layer = 2;
    rock.useSlope = true;
    rock.slopeMin = 35.0;
    rock.slopeMax = 90.0;
    rock.slopeBlend = 0.0;
    const RulePreview p = previewRule(t.height, rock, 51);
    QCOMPARE(p.width, 51);
    QCOMPARE(p.height, 51);
    // The east half is a 45-degree ramp: about half the terrain.
    QVERIFY2(p.coverage > 0.45 && p.coverage < 0.55, qPrintable(QString::number(p.coverage)));
    QCOMPARE(p.full, p.coverage);
    QCOMPARE(p.weights[size_t(25) * 51 + 50], 1.0f);  // east edge
    QCOMPARE(p.weights[size_t(25) * 51 + 0], 0.0f);   // west edge
    rock.enabled = false;
    QCOMPARE(previewRule(t.height, rock, 51).coverage, 0.0);
    // Smaller terrains than the preview are read sample for sample.
    Terrain small = make(17, 16.0);
    QCOMPARE(previewRule(small.height, rock, 96).width, 17);
  }
};

QTEST_GUILESS_MAIN(TestPaint)
#include "test_terrain_paint.moc"
