// Undo: strokes store only touched tiles, undo restores bitwise, the memory
// cap drops the oldest steps first.
#include <QtTest>

#include <cstring>
#include <random>

#include "terrain/paint_rules.h"
#include "terrain/stroke.h"
#include "terrain/undo_history.h"

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
    const size_t cap = size_t(64) << 20;
    UndoHistory history(cap);
    std::mt19937 rng(2024);
    std::vector<Terrain> afterEach;  // a few checkpoints for redo
    for (int i = 0; i < 100; ++i) {
      UndoStep step = randomStroke(t, rng);
      QVERIFY(step.tileCount() <= size_t(t.height.heights().tileCount()) * (2 + size_t(t.paint.layerCount())));
      const UndoPushResult r = history.push(std::move(step));
      QVERIFY(r.kept);
      QVERIFY(history.bytesUsed() <= cap);
    }
    QCOMPARE(history.droppedTotal(), size_t(0));
    qInfo("100 strokes: %zu steps, %.1f MiB of undo (cap %zu MiB)", history.undoSteps(),
          double(history.bytesUsed()) / 1048576.0, cap >> 20);
    const Terrain edited = t.clone();
    QVERIFY(!identical(edited, original));
    while (history.canUndo()) history.undo(t);
    QVERIFY(identical(t, original));
    while (history.canRedo()) history.redo(t);
    QVERIFY(identical(t, edited));
    QVERIFY(history.bytesUsed() <= cap);
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

  void capDropsOldestFirst() {
    Terrain t = make(257, 256.0);
    const Terrain original = t.clone();
    BrushSettings s;
    s.tool = BrushTool::Raise;
    s.radius = 5.0;
    auto strokeAt = [&](double x, double y) {
      Stroke st(t, s);
      st.dabAt({x, y});
      return st.finish();
    };
    const size_t one = strokeAt(30.0, 30.0).bytes();  // measure, then put back
    t = original.clone();
    UndoHistory h(3 * one + one / 2);  // room for three steps
    h.push(strokeAt(30.0, 30.0));
    const Terrain afterFirst = t.clone();
    h.push(strokeAt(30.0, 200.0));
    h.push(strokeAt(200.0, 30.0));
    const UndoPushResult r = h.push(strokeAt(200.0, 200.0));
    QCOMPARE(r.droppedSteps, size_t(1));
    QCOMPARE(h.undoSteps(), size_t(3));
    QVERIFY(h.bytesUsed() <= h.cap());
    while (h.canUndo()) h.undo(t);
    QVERIFY(identical(t, afterFirst));  // the first stroke can no longer be undone
    // A step larger than the whole cap is not kept, and says so.
    UndoHistory tiny(100);
    QVERIFY(!tiny.push(strokeAt(100.0, 100.0)).kept);
    QCOMPARE(tiny.undoSteps(), size_t(0));
    // Lowering the cap trims.
    h.setCap(one + one / 2);
    QVERIFY(h.bytesUsed() <= h.cap());
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
