// Erosion: mass conservation, stability at extreme settings, determinism
// across thread counts, masks, cancellation.
#include <QtTest>

#include <cmath>
#include <random>

#include "erosion_mass.h"
#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"
#include "terrain/stroke.h"
#include "terrain/undo_step.h"

using namespace hs::terrain;

namespace {

// Rolling hills on a 100 m base: a field with slopes of every angle.
std::vector<float> hills(int w, int h, unsigned seed = 1) {
  std::vector<float> v(size_t(w) * size_t(h));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      v[size_t(y) * size_t(w) + size_t(x)] =
          100.0f + 20.0f * std::sin(float(x) * 0.15f) * std::cos(float(y) * 0.11f) + float(x) * 0.2f + u(rng);
  return v;
}

bool allFinite(const std::vector<float>& v) {
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// Whether `r` conserved mass to `tolerance` of the `moved` m^3 the run
// moved (exactly, when it moved nothing); `why` says what was measured
// either way. Tolerances: tests/common/erosion_mass.h.
bool massConserved(const ErosionReport& r, double moved, const char* what, QByteArray& why,
                   double tolerance = hs::test::kErosionMassTolerance) {
  const double ratio = moved > 0.0 ? r.massError / moved : r.massError;
  why = QByteArray(what) + ": mass error " + QByteArray::number(r.massError, 'g', 3) + " m^3, moved " +
        QByteArray::number(moved, 'g', 4) + " m^3, ratio " + QByteArray::number(ratio, 'g', 3) + " (allowed " +
        QByteArray::number(tolerance, 'g', 2) + ")";
  qInfo("%s", why.constData());
  return moved > 0.0 ? ratio < tolerance : r.massError == 0.0;
}

Terrain make(int n, double size) {
  HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {size, size};
  auto r = Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  return r.take();
}

}  // namespace

class TestErosion : public QObject {
  Q_OBJECT
 private slots:
  void thermalConservesMass() {
    std::vector<float> h = hills(64, 64);
    const std::vector<float> h0 = h;
    ThermalParams p;
    p.talusDegrees = 20.0;
    p.iterations = 1000;
    p.strength = 1.0f;
    const ErosionReport r = erodeThermalGrid(h, 64, 64, {1.0, 1.0}, p, nullptr);
    QCOMPARE(r.iterationsDone, 1000);
    QByteArray why;
    QVERIFY2(massConserved(r, hs::test::movedVolume(h0, h, 1.0), "thermal 1000 it", why), why);
    // It did something: slopes now at most about the talus angle.
    double steepest = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 1; x < 64; ++x)
        steepest = std::max(steepest, double(std::abs(h[size_t(y) * 64 + size_t(x)] - h[size_t(y) * 64 + size_t(x) - 1])));
    QVERIFY2(steepest < std::tan(20.0 * M_PI / 180.0) * 1.5, qPrintable(QString::number(steepest)));
  }

  void hydraulicConservesMass() {
    std::vector<float> h = hills(64, 64);
    HydraulicParams p;
    p.iterations = 1000;
    const ErosionReport r = erodeHydraulicGrid(h, 64, 64, {1.0, 1.0}, p, nullptr);
    QCOMPARE(r.iterationsDone, 1000);
    qInfo("hydraulic 1000 it: dt %.3g..%.3g, CFL-limited %d", r.minDt, r.maxDt, r.cflLimitedIterations);
    const double moved = hs::test::movedVolume(hills(64, 64), h, 1.0);
    QVERIFY2(moved > 1.0, qPrintable(QString("material moved: %1 m^3").arg(moved)));
    QByteArray why;
    QVERIFY2(massConserved(r, moved, "hydraulic 1000 it", why), why);
  }

  void extremeThermal() {
    for (double talus : {0.0, 90.0, -45.0, 1e9, double(NAN)}) {
      std::vector<float> h = hills(32, 32);
      const std::vector<float> h0 = h;
      ThermalParams p{talus, 200, 1.0f};
      const ErosionReport r = erodeThermalGrid(h, 32, 32, {1.0, 1.0}, p, nullptr);
      QVERIFY(allFinite(h));
      QByteArray why;
      QVERIFY2(massConserved(r, hs::test::movedVolume(h0, h, 1.0), qPrintable(QString("thermal, talus %1").arg(talus)), why),
               why);
      if (talus >= 90.0) QVERIFY(h == h0);  // nothing is steeper than vertical
      if (!(talus >= 0.0 && talus <= 90.0)) QVERIFY(!r.warnings.empty());  // clamped and said so
    }
    // Talus 0 flattens toward the mean without overshoot: no new extremes.
    std::vector<float> h = hills(32, 32);
    const float lo = *std::min_element(h.begin(), h.end()), hi = *std::max_element(h.begin(), h.end());
    erodeThermalGrid(h, 32, 32, {1.0, 1.0}, ThermalParams{0.0, 2000, 1.0f}, nullptr);
    QVERIFY(*std::min_element(h.begin(), h.end()) >= lo);
    QVERIFY(*std::max_element(h.begin(), h.end()) <= hi);
  }

  void extremeHydraulic() {
    // Rain 1e6 m/s.
    {
      std::vector<float> h = hills(24, 24);
      HydraulicParams p;
      p.rain = 1e6;
      p.iterations = 300;
      const ErosionReport r = erodeHydraulicGrid(h, 24, 24, {1.0, 1.0}, p, nullptr);
      QVERIFY(allFinite(h));
      QVERIFY(r.cflLimitedIterations > 0);
      QVERIFY(!r.warnings.empty());  // rain is capped at 1000 m/s, and the run says so
      // So much water that the flow stalls and almost nothing moves: the
      // error is bounded by float rounding, not by the volume moved.
      const double allowed = hs::test::oneRoundingPerCell(h, 1.0);
      qInfo("hydraulic, rain 1e6 m/s: mass error %.3g m^3, moved %.3g m^3, allowed %.3g m^3 (one rounding per cell)",
            r.massError, hs::test::movedVolume(hills(24, 24), h, 1.0), allowed);
      QVERIFY(r.massError < allowed);
    }
    // 1e5 iterations on a small grid.
    {
      std::vector<float> h = hills(12, 12);
      HydraulicParams p;
      p.iterations = 100000;
      const ErosionReport r = erodeHydraulicGrid(h, 12, 12, {1.0, 1.0}, p, nullptr);
      QCOMPARE(r.iterationsDone, 100000);
      QVERIFY(allFinite(h));
      QByteArray why;
      QVERIFY2(massConserved(r, hs::test::movedVolume(hills(12, 12), h, 1.0), "hydraulic 1e5 it on 12x12", why,
                             hs::test::kLongRunMassTolerance),
               why);
      std::vector<float> t = hills(12, 12);
      const ErosionReport rt = erodeThermalGrid(t, 12, 12, {1.0, 1.0}, ThermalParams{30.0, 100000, 1.0f}, nullptr);
      QVERIFY(allFinite(t));
      QVERIFY2(massConserved(rt, hs::test::movedVolume(hills(12, 12), t, 1.0), "thermal 1e5 it on 12x12", why,
                             hs::test::kLongRunMassTolerance),
               why);
    }
    // Every rate at its extreme, huge time step.
    {
      std::vector<float> h = hills(24, 24);
      HydraulicParams p;
      p.timeStep = 1e9;
      p.evaporation = 1e9;
      p.erosionRate = 1e9;
      p.depositionRate = 1e9;
      p.sedimentCapacity = 1e9;
      p.iterations = 200;
      erodeHydraulicGrid(h, 24, 24, {1.0, 1.0}, p, nullptr);
      QVERIFY(allFinite(h));
      p.evaporation = 0.0;
      p.rain = 10.0;
      erodeHydraulicGrid(h, 24, 24, {1.0, 1.0}, p, nullptr);
      QVERIFY(allFinite(h));
    }
  }

  void verticalCliffAndFlatField() {
    // A 100 m wall between two plateaus, 1 m grid.
    std::vector<float> cliff(40 * 40);
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) cliff[size_t(y) * 40 + size_t(x)] = x < 20 ? 100.0f : 0.0f;
    std::vector<float> c1 = cliff, c2 = cliff;
    const ErosionReport rt = erodeThermalGrid(c1, 40, 40, {1.0, 1.0}, ThermalParams{35.0, 500, 1.0f}, nullptr);
    QVERIFY(allFinite(c1));
    QByteArray why;
    QVERIFY2(massConserved(rt, hs::test::movedVolume(cliff, c1, 1.0), "thermal, 100 m cliff", why), why);
    QVERIFY(c1[20 * 40 + 19] < 100.0f && c1[20 * 40 + 20] > 0.0f);  // the wall slumped
    HydraulicParams hp;
    hp.iterations = 500;
    const ErosionReport rh = erodeHydraulicGrid(c2, 40, 40, {1.0, 1.0}, hp, nullptr);
    QVERIFY(allFinite(c2));
    QVERIFY2(massConserved(rh, hs::test::movedVolume(cliff, c2, 1.0), "hydraulic, 100 m cliff", why,
                           hs::test::kLittleMovedMassTolerance),
             why);

    // A perfectly flat field stays flat under thermal erosion, and finite
    // (and level, since rain falls evenly) under hydraulic erosion.
    std::vector<float> flat(32 * 32, 50.0f);
    erodeThermalGrid(flat, 32, 32, {1.0, 1.0}, ThermalParams{0.0, 100, 1.0f}, nullptr);
    for (float v : flat) QCOMPARE(v, 50.0f);
    std::vector<float> flat2(32 * 32, 50.0f);
    erodeHydraulicGrid(flat2, 32, 32, {1.0, 1.0}, HydraulicParams{}, nullptr);
    for (float v : flat2) QVERIFY(std::abs(v - 50.0f) < 1e-3f);
  }

  // sanitized() clamps to the declared ranges (the CLI and the dialog
  // refuse outside them), each change with a warning naming it.
  void sanitizeClampsByTheDeclarations() {
    std::vector<std::string> w;
    const ThermalParams t = ThermalParams{95.0, 0, 2.0f}.sanitized(w);
    const std::vector<hs::ParamDecl>& td = thermalParamDecls();
    QCOMPARE(t.talusDegrees, paramIn(td, "talus_deg").max);
    QCOMPARE(double(t.iterations), paramIn(td, "iterations").min);
    QCOMPARE(double(t.strength), paramIn(td, "strength").max);
    QCOMPARE(w.size(), size_t(3));
    QVERIFY2(w[0].find("Talus angle 95 is out of range (0 to 90 degrees); using 90") != std::string::npos, w[0].c_str());
    w.clear();
    HydraulicParams h;
    h.timeStep = 1e9;
    h.rain = -1.0;
    const HydraulicParams hc = h.sanitized(w);
    const std::vector<hs::ParamDecl>& hd = hydraulicParamDecls();
    QCOMPARE(hc.timeStep, paramIn(hd, "time_step_s").max);
    QCOMPARE(hc.rain, paramIn(hd, "rain_m_per_s").min);
    QCOMPARE(w.size(), size_t(2));
    // Values in range pass untouched, defaults included.
    w.clear();
    QCOMPARE(ThermalParams{}.sanitized(w).talusDegrees, ThermalParams{}.talusDegrees);
    QCOMPARE(HydraulicParams{}.sanitized(w).iterations, HydraulicParams{}.iterations);
    QVERIFY(w.empty());
    // One --iterations for both solvers: their declared ranges agree.
    QCOMPARE(paramIn(td, "iterations").min, paramIn(hd, "iterations").min);
    QCOMPARE(paramIn(td, "iterations").max, paramIn(hd, "iterations").max);
  }

  void nanInputs() {
    std::vector<float> h = hills(32, 32);
    h[100] = NAN;
    h[101] = INFINITY;
    h[500] = -INFINITY;
    HydraulicParams p;
    p.rain = NAN;
    p.timeStep = NAN;
    p.iterations = 100;
    p.cfl = NAN;
    const ErosionReport r = erodeHydraulicGrid(h, 32, 32, {1.0, 1.0}, p, nullptr);
    QVERIFY(allFinite(h));
    QCOMPARE(r.nonFiniteHeightsFixed, size_t(3));
    QVERIFY(r.warnings.size() >= 4);
    std::vector<float> t = hills(32, 32);
    t[7] = NAN;
    const ErosionReport rt = erodeThermalGrid(t, 32, 32, {NAN, 1.0}, ThermalParams{NAN, 50, NAN}, nullptr);
    QVERIFY(allFinite(t));
    QCOMPARE(rt.nonFiniteHeightsFixed, size_t(1));
  }

  void deterministicAcrossThreadCounts() {
    for (int solver = 0; solver < 2; ++solver) {
      std::vector<float> a = hills(150, 130), b = a;
      if (solver == 0) {
        erodeThermalGrid(a, 150, 130, {2.0, 1.5}, ThermalParams{25.0, 100, 0.7f}, nullptr, nullptr, 1);
        erodeThermalGrid(b, 150, 130, {2.0, 1.5}, ThermalParams{25.0, 100, 0.7f}, nullptr, nullptr, 2);
      } else {
        HydraulicParams p;
        p.iterations = 100;
        erodeHydraulicGrid(a, 150, 130, {2.0, 1.5}, p, nullptr, nullptr, 1);
        erodeHydraulicGrid(b, 150, 130, {2.0, 1.5}, p, nullptr, nullptr, 2);
      }
      QVERIFY(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
    }
  }

  void maskedBrushTouchesOnlyItsRegion() {
    Terrain t = make(257, 256.0);
    const std::vector<float> h = hills(257, 257);
    t.height.write(t.height.bounds(), h);
    const Heightfield before = t.height.clone();
    UndoRecorder rec(t);
    FalloffCurve c;
    const ErosionMask m = ErosionMask::circle(t.height, {128.0, 128.0}, 40.0, c);
    const ErosionReport r = erodeHydraulic(t.height, HydraulicParams{}, m, &rec);
    QCOMPARE(r.changed, m.region);
    bool changed = false;
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) {
        if (!m.region.contains(x, y)) QCOMPARE(t.height.at(x, y), before.at(x, y));
        changed |= t.height.at(x, y) != before.at(x, y);
      }
    QVERIFY(changed);
    UndoStep step = rec.finish("erode");
    step.swap(t);
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x) QCOMPARE(t.height.at(x, y), before.at(x, y));

    // As a brush stroke.
    BrushSettings s;
    s.tool = BrushTool::ThermalErosion;
    s.radius = 30.0;
    s.strength = 1.0f;
    s.thermal = {10.0, 20, 1.0f};
    Stroke st(t, s);
    const Heightfield beforeDab = t.height.clone();
    const StrokeUpdate u = st.dabAt({100.0, 100.0});
    QVERIFY(!u.changed.empty());
    ErosionReport dab;
    dab.massError = u.erosionMassError;
    QByteArray why;
    QVERIFY2(massConserved(dab, hs::test::movedVolume(beforeDab, t.height), "thermal erosion brush dab", why), why);
  }

  void paintLayerMask() {
    // Erode only where "Scree" (layer 4) is painted: the west half.
    Terrain t = make(129, 128.0);
    t.height.write(t.height.bounds(), hills(129, 129));
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 64; ++x) t.paint.blend(x, y, 4, 1.0f);
    const Heightfield before = t.height.clone();
    const ErosionMask m = ErosionMask::fromPaintLayer(t.paint, 4);
    QCOMPARE(m.region, t.height.bounds());
    const ErosionReport r = erodeThermal(t.height, ThermalParams{10.0, 50, 1.0f}, m);
    QByteArray why;
    QVERIFY2(massConserved(r, hs::test::movedVolume(before, t.height), "thermal under a paint-layer mask", why), why);
    bool west = false;
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x) {
        if (x >= 64) QCOMPARE(t.height.at(x, y), before.at(x, y));
        else west |= t.height.at(x, y) != before.at(x, y);
      }
    QVERIFY(west);
  }

  void cancelLeavesTerrainUnchanged() {
    Terrain t = make(129, 128.0);
    t.height.write(t.height.bounds(), hills(129, 129));
    const Heightfield before = t.height.clone();
    hs::Progress progress;
    progress.cancel();
    HydraulicParams p;
    p.iterations = 1000;
    const ErosionReport r = erodeHydraulic(t.height, p, ErosionMask::whole(t.height), nullptr, &progress);
    QVERIFY(r.cancelled);
    const ErosionReport r2 = erodeThermal(t.height, ThermalParams{}, ErosionMask::whole(t.height), nullptr, &progress);
    QVERIFY(r2.cancelled);
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x) QCOMPARE(t.height.at(x, y), before.at(x, y));
  }
};

QTEST_GUILESS_MAIN(TestErosion)
#include "test_terrain_erosion.moc"
