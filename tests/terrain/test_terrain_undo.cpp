// Undo: strokes store only touched tiles, undo restores bitwise, the memory
// cap drops the oldest steps first.
#include <QtTest>

#include <cstring>
#include <random>

#include "terrain/paint_rules.h"
#include "terrain/stroke.h"

using namespace hs::terrain;

namespace {

Terrain make(int n, double size) {
  HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {size, size};
  auto r = Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  Terrain t = r.take();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 30.f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) t.height.heights().set(x, y, u(rng));
  t.height.updateAllBounds();
  return t;
}

// Bitwise comparison of everything a stroke can change.
bool identical(const Terrain& a, const Terrain& b) {
  for (int y = 0; y < a.height.samplesY(); ++y)
    for (int x = 0; x < a.height.samplesX(); ++x) {
      const float ha = a.height.at(x, y), hb = b.height.at(x, y);
      if (std::memcmp(&ha, &hb, sizeof(float)) != 0) return false;
      if (a.height.isHole(x, y) != b.height.isHole(x, y)) return false;
      for (int l = 0; l < a.paint.layerCount(); ++l)
        if (a.paint.raw(l, x, y) != b.paint.raw(l, x, y)) return false;
    }
  for (int t = 0; t < a.height.heights().tileCount(); ++t) {
    const HeightRange ra = a.height.tileBounds(t), rb = b.height.tileBounds(t);
    if (ra.min != rb.min || ra.max != rb.max) return false;
  }
  return true;
}

UndoStep randomStroke(Terrain& t, std::mt19937& rng) {
  const BrushTool tools[] = {BrushTool::Raise, BrushTool::Lower, BrushTool::Smooth, BrushTool::Flatten,
                             BrushTool::Noise, BrushTool::Terrace, BrushTool::Paint, BrushTool::Holes,
                             BrushTool::ThermalErosion, BrushTool::HydraulicErosion};
  std::uniform_int_distribution<int> tool(0, 9), layer(0, 7), points(1, 6);
  std::uniform_real_distribution<double> pos(-20.0, 420.0), rad(3.0, 60.0);
  std::uniform_real_distribution<float> str(0.05f, 1.0f), pr(0.1f, 1.0f);
  BrushSettings s;
  s.tool = tools[tool(rng)];
  s.radius = rad(rng);
  s.strength = str(rng);
  s.paintLayer = layer(rng);
  s.erase = (rng() & 3) == 0;
  s.noise.seed = rng();
  s.hydraulicIterationsPerDab = 5;
  s.thermal.iterations = 3;
  Stroke st(t, s);
  const int n = points(rng);
  for (int i = 0; i < n; ++i) st.moveTo({pos(rng), pos(rng)}, pr(rng));
  return st.finish();
}

}  // namespace

class TestUndo : public QObject {
  Q_OBJECT
 private slots:
  void hundredRandomStrokesUndoExactly() {
    Terrain t = make(385, 384.0);  // 4 x 4 tiles
    const Terrain original = t.clone();
    std::mt19937 rng(2024);
    std::vector<UndoStep> steps;  // the undo history, oldest first
    size_t bytes = 0;
    for (int i = 0; i < 100; ++i) {
      UndoStep step = randomStroke(t, rng);
      QVERIFY(step.tileCount() <= size_t(t.height.heights().tileCount()) * (2 + size_t(t.paint.layerCount())));
      bytes += step.bytes();
      steps.push_back(std::move(step));
    }
    qInfo("100 strokes: %.1f MiB of undo", double(bytes) / 1048576.0);
    const Terrain edited = t.clone();
    QVERIFY(!identical(edited, original));
    for (auto it = steps.rbegin(); it != steps.rend(); ++it) it->swap(t);  // undo all, newest first
    QVERIFY(identical(t, original));
    for (auto& step : steps) step.swap(t);  // redo all, oldest first
    QVERIFY(identical(t, edited));
  }

  void strokeStoresOnlyTouchedTiles() {
    Terrain t = make(513, 512.0);  // 5 x 5 tiles (the last one sample wide)
    BrushSettings s;
    s.tool = BrushTool::Raise;
    s.radius = 10.0;
    Stroke st(t, s);
    st.dabAt({64.0, 64.0});  // inside tile 0 only
    UndoStep step = st.finish();
    QCOMPARE(step.tileCount(), size_t(1));
    QVERIFY(step.bytes() >= TileGrid<float>::tileBytes());
    QVERIFY(step.bytes() < TileGrid<float>::tileBytes() + 4096);
    Stroke s2(t, s);
    s2.dabAt({128.0, 128.0});  // on a tile corner: 4 tiles
    QCOMPARE(s2.finish().tileCount(), size_t(4));
  }

  void paintRulesAreOneUndoStep() {
    Terrain t = make(200, 199.0);
    const Terrain original = t.clone();
    PaintRule r;
    r.layer = 3;
    r.useAltitude = true;
    r.altitudeMin = 10.0;
    r.altitudeMax = 20.0;
    PaintRulesResult res = applyPaintRules(t, {r});
    QVERIFY(res.ok());
    QVERIFY(!identical(t, original));
    res.undo.swap(t);
    QVERIFY(identical(t, original));
  }
};

QTEST_GUILESS_MAIN(TestUndo)
#include "test_terrain_undo.moc"
