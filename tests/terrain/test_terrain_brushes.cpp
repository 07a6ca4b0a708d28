// Each sculpt tool's effect on a known field.
#include <QtTest>

#include <cmath>
#include <random>

#include "terrain/stroke.h"

using namespace hs::terrain;

namespace {

Terrain make(int n, double size, float h0 = 0.0f) {
  HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {size, size};
  d.initialHeight = h0;
  auto r = Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  return r.take();
}

void fillRandom(Heightfield& hf, unsigned seed, float amp) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amp, amp);
  for (int y = 0; y < hf.samplesY(); ++y)
    for (int x = 0; x < hf.samplesX(); ++x) hf.heights().set(x, y, u(rng));
  hf.updateAllBounds();
}

float maxHeight(const Heightfield& hf) {
  float m = -INFINITY;
  for (int y = 0; y < hf.samplesY(); ++y)
    for (int x = 0; x < hf.samplesX(); ++x) m = std::max(m, hf.at(x, y));
  return m;
}

// Every sample that differs between a and b lies in `r`.
bool changesInside(const Heightfield& a, const Heightfield& b, const Region& r) {
  for (int y = 0; y < a.samplesY(); ++y)
    for (int x = 0; x < a.samplesX(); ++x)
      if (a.at(x, y) != b.at(x, y) && !r.contains(x, y)) return false;
  return true;
}

BrushSettings brush(BrushTool tool, double radius, float strength) {
  BrushSettings s;
  s.tool = tool;
  s.radius = radius;
  s.strength = strength;
  return s;
}

}  // namespace

class TestBrushes : public QObject {
  Q_OBJECT
 private slots:
  void raiseAddsStrengthWithFalloff() {
    Terrain t = make(129, 128.0, 10.0f);  // 1 m spacing
    BrushSettings s = brush(BrushTool::Raise, 20.0, 2.5f);
    s.falloff.shape = FalloffShape::Linear;
    s.falloff.falloff = 1.0f;  // weight = 1 - r / R
    const Heightfield before = t.height.clone();
    Stroke st(t, s);
    const StrokeUpdate u = st.dabAt({64.0, 64.0});
    QCOMPARE(t.height.at(64, 64), 12.5f);  // exactly s at the centre
    for (int y = 40; y < 90; ++y)
      for (int x = 40; x < 90; ++x) {
        const double r = std::hypot(x - 64.0, y - 64.0) / 20.0;
        const double expect = 10.0 + (r < 1.0 ? 2.5 * (1.0 - r) : 0.0);
        QVERIFY2(std::abs(double(t.height.at(x, y)) - expect) < 2e-3,
                 qPrintable(QString("%1,%2: %3 vs %4").arg(x).arg(y).arg(t.height.at(x, y)).arg(expect)));
      }
    QCOMPARE(u.changed, (Region{45, 45, 84, 84}));  // |d| < 20 samples
    QCOMPARE(u.changedBytes, size_t(39 * 39 * 4));
    QVERIFY(changesInside(before, t.height, u.changed));
    QCOMPARE(t.height.range().max, 12.5f);  // bounds updated

    // Lower is the mirror; pressure scales strength.
    BrushSettings l = brush(BrushTool::Lower, 20.0, 2.5f);
    Stroke sl(t, l);
    sl.dabAt({64.0, 64.0}, 0.5f);
    QCOMPARE(t.height.at(64, 64), 11.25f);
  }

  void smoothNeverRaisesAMaximum() {
    Terrain t = make(200, 199.0);
    fillRandom(t.height, 3, 50.0f);
    const float max0 = maxHeight(t.height);
    double rough0 = 0, rough1 = 0;
    for (int x = 1; x < 199; ++x) rough0 += std::abs(double(t.height.at(x, 100)) - double(t.height.at(x - 1, 100)));
    BrushSettings s = brush(BrushTool::Smooth, 30.0, 1.0f);
    for (int k = 0; k < 3; ++k) {
      Stroke st(t, s);
      st.moveTo({20.0, 100.0});
      st.moveTo({180.0, 100.0});
      st.moveTo({100.0, 190.0});
      st.finish();
      QVERIFY(maxHeight(t.height) <= max0);
    }
    for (int x = 1; x < 199; ++x) rough1 += std::abs(double(t.height.at(x, 100)) - double(t.height.at(x - 1, 100)));
    QVERIFY2(rough1 < 0.3 * rough0, qPrintable(QString("roughness %1 -> %2").arg(rough0).arg(rough1)));
    // A single spike: smoothing lowers it, never above.
    Terrain p = make(65, 64.0);
    p.height.set(32, 32, 100.0f);
    Stroke st(p, brush(BrushTool::Smooth, 10.0, 1.0f));
    st.dabAt({32.0, 32.0});
    QVERIFY(p.height.at(32, 32) < 100.0f);
    QVERIFY(maxHeight(p.height) <= 100.0f);
  }

  void flattenReachesTheTarget() {
    Terrain t = make(129, 128.0);
    fillRandom(t.height, 5, 20.0f);
    BrushSettings s = brush(BrushTool::Flatten, 15.0, 1.0f);
    s.falloff.falloff = 0.0f;  // full weight inside the radius
    s.flattenHeight = 7.25f;
    const Heightfield before = t.height.clone();
    Stroke st(t, s);
    const StrokeUpdate u = st.dabAt({60.3, 70.7});
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x) {
        const double r = std::hypot(x - 60.3, y - 70.7);
        if (r < 14.999) QCOMPARE(t.height.at(x, y), 7.25f);
        if (r > 15.001) QCOMPARE(t.height.at(x, y), before.at(x, y));
      }
    QVERIFY(changesInside(before, t.height, u.changed));

    // Picked height: the height under the first dab, kept for the stroke.
    Terrain q = make(129, 128.0);
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x) q.height.heights().set(x, y, float(x) * 0.5f);
    q.height.updateAllBounds();
    BrushSettings p = brush(BrushTool::Flatten, 10.0, 1.0f);
    p.falloff.falloff = 0.0f;
    Stroke sp(q, p);
    sp.moveTo({40.0, 64.0});
    sp.moveTo({80.0, 64.0});  // dabs along x keep the first target (20 m)
    QCOMPARE(q.height.at(80, 64), 20.0f);
    QCOMPARE(q.height.at(40, 60), 20.0f);

    // Along the slope: a tilted plane stays (nearly) itself; a bump on it goes.
    Terrain r = make(129, 128.0);
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x)
        r.height.heights().set(x, y, float(0.3 * x + 0.1 * y + 5.0 * std::exp(-((x - 64.0) * (x - 64.0) + (y - 64.0) * (y - 64.0)) / 8.0)));
    r.height.updateAllBounds();
    BrushSettings sl = brush(BrushTool::Flatten, 30.0, 1.0f);
    sl.falloff.falloff = 0.0f;
    sl.flattenMode = FlattenMode::Slope;
    Stroke ss(r, sl);
    ss.dabAt({64.0, 64.0});
    // The fitted plane is pulled up a little by the bump; the slope is kept.
    const double slopeX = double(r.height.at(74, 64)) - double(r.height.at(54, 64));
    QVERIFY2(std::abs(slopeX - 6.0) < 0.05, qPrintable(QString::number(slopeX)));
    QVERIFY(double(r.height.at(64, 64)) - (0.3 * 64 + 0.1 * 64) < 0.5);  // the bump (5 m) is gone
  }

  void rampIsLinearBetweenItsPoints() {
    Terrain t = make(257, 256.0);
    fillRandom(t.height, 9, 3.0f);
    RampSettings s;
    s.a = {30.0, 40.0, 10.0};
    s.b = {220.0, 200.0, 70.0};
    s.width = 20.0;
    s.falloff = 0.5f;
    const Heightfield before = t.height.clone();
    RampResult res = applyRamp(t, s);
    QVERIFY(res.ok());
    const double len = glm::length(glm::dvec2(s.b - s.a));
    const glm::dvec2 dir = glm::dvec2(s.b - s.a) / len;
    int checked = 0;
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) {
        const glm::dvec2 p(x, y);
        const double u = glm::dot(p - glm::dvec2(s.a), dir);
        const double side = std::abs(glm::dot(p - glm::dvec2(s.a), glm::dvec2(-dir.y, dir.x)));
        if (u < 0 || u > len || side > 4.9) continue;  // inner half-width = 5 m
        const double expect = 10.0 + 60.0 * u / len;
        QVERIFY2(std::abs(double(t.height.at(x, y)) - expect) < 1e-5 * 70.0,
                 qPrintable(QString("%1,%2: %3 vs %4").arg(x).arg(y).arg(t.height.at(x, y)).arg(expect)));
        ++checked;
      }
    QVERIFY(checked > 1500);
    QVERIFY(changesInside(before, t.height, res.changed));
    QVERIFY(!res.undo.empty());
    res.undo.swap(t);  // undo
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) QCOMPARE(t.height.at(x, y), before.at(x, y));
    // Degenerate ramps are refused with a message.
    s.b = s.a;
    QVERIFY(!applyRamp(t, s).ok());
    s.b = {NAN, 0.0, 0.0};
    QVERIFY(!applyRamp(t, s).ok());
  }

  void noiseIsDeterministicAndBounded() {
    auto run = [](uint64_t seed, int threads) {
      Terrain t = make(257, 256.0);
      BrushSettings s = brush(BrushTool::Noise, 100.0, 4.0f);
      s.noise.seed = seed;
      s.noise.scale = 20.0;
      Stroke st(t, s, threads);
      st.moveTo({50.0, 128.0});
      st.moveTo({200.0, 128.0});
      st.finish();
      return t;
    };
    Terrain a = run(42, 1), b = run(42, 2), c = run(43, 2);
    bool differs = false;
    float peak = 0.0f;
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) {
        QCOMPARE(a.height.at(x, y), b.height.at(x, y));  // bitwise, any thread count
        differs |= a.height.at(x, y) != c.height.at(x, y);
        peak = std::max(peak, std::abs(a.height.at(x, y)));
      }
    QVERIFY(differs);
    QVERIFY(peak > 1.0f);
    // Each dab adds at most strength; the stroke had < 30 dabs over any sample.
    QVERIFY(peak < 4.0f * 30.0f);
  }

  void terraceConverges() {
    Terrain t = make(129, 128.0);
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x) t.height.heights().set(x, y, float(x) * 0.37f);
    t.height.updateAllBounds();
    const Heightfield before = t.height.clone();
    BrushSettings s = brush(BrushTool::Terrace, 40.0, 1.0f);
    s.falloff.falloff = 0.0f;
    s.terrace = {5.0f, 0.0f, 0.8f};
    Stroke st(t, s);
    for (int k = 0; k < 5; ++k) st.dabAt({64.0, 64.0});  // repeated dabs converge
    for (int x = 30; x < 100; ++x) {
      const float expect = terraceHeight(before.at(x, 64), s.terrace);
      QCOMPARE(t.height.at(x, 64), expect);
    }
    QCOMPARE(terraceHeight(7.0f, {5.0f, 0.0f, 1.0f}), 5.0f);   // hard steps
    QCOMPARE(terraceHeight(7.0f, {5.0f, 0.0f, 0.0f}), 7.0f);   // no terrace
    QCOMPARE(terraceHeight(9.5f, {5.0f, 0.0f, 0.8f}), 7.5f);   // riser: f=0.9 -> 0.5
  }

  void penSpacing() {
    Terrain t = make(257, 256.0);
    BrushSettings s = brush(BrushTool::Raise, 8.0, 0.1f);
    s.spacing = 0.25f;  // a dab every 2 m
    Stroke st(t, s);
    int dabs = st.moveTo({20.0, 50.0}).dabs;
    QCOMPARE(dabs, 1);
    dabs += st.moveTo({21.0, 50.0}).dabs;  // 1 m: no dab yet
    QCOMPARE(dabs, 1);
    dabs += st.moveTo({120.0, 50.0}).dabs;  // 100 m from the start: 50 more
    QCOMPARE(dabs, 51);
    dabs += st.moveTo({120.0, 51.0}).dabs;  // the remainder carries over the corner
    QCOMPARE(dabs, 51);
    dabs += st.moveTo({120.0, 52.5}).dabs;
    QCOMPARE(dabs, 52);
    QCOMPARE(st.dabCount(), 52);
  }

  void extremeAndInvalidSettings() {
    Terrain t = make(65, 64.0);
    BrushSettings s = brush(BrushTool::Raise, NAN, NAN);
    s.spacing = -5.0f;
    s.falloff.falloff = NAN;
    Stroke st(t, s);
    QVERIFY(!st.warnings().empty());
    st.moveTo({32.0, 32.0});
    st.moveTo({INFINITY, 32.0});  // ignored
    st.moveTo({1e300, 1e300});    // off the terrain: no dab lands
    for (int y = 0; y < 65; ++y)
      for (int x = 0; x < 65; ++x) QVERIFY(std::isfinite(t.height.at(x, y)));
    // A radius larger than the terrain is clamped to its extent (64 m), a
    // dab off the edge is clipped to the grid.
    BrushSettings big = brush(BrushTool::Raise, 1e9, 1.0f);
    Stroke sb(t, big);
    QCOMPARE(sb.dabAt({-10.0, -10.0}).changed, (Region{0, 0, 54, 54}));
  }
};

QTEST_GUILESS_MAIN(TestBrushes)
#include "test_terrain_brushes.moc"
