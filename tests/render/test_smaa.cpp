// SMAA (render/passes/smaa_passes.h, docs/rendering.md "Anti-aliasing"):
// the CPU twin's outline areas against the exact coverage of straight edges
// (what the method promises: far below the aliased picture's error; near
// 45° through the diagonal patterns), rectangles' corners kept, the
// renderer's passes against the twin on the renderer's own aliased frame,
// the frame against a 4x4 supersampled render of the same view (SMAA nearer
// to it than no anti-aliasing, FXAA printed beside), and no SMAA pass or
// texture unless chosen.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pass_stats.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "post_scene.h"
#include "smaa_reference.h"

using namespace hs;
using test::passRan;

namespace {

// A white half-plane over black, y = slope·x + offset in pixels (rows
// upwards from the bottom), point sampled at pixel centres, and its exact
// coverage per pixel (8 × 8 subsamples per pixel would be approximate:
// the area is integrated over each column analytically).
struct HalfPlane {
  Image aliased, exact;
};

HalfPlane halfPlane(int w, int h, double slope, double offset) {
  HalfPlane out{Image::make8(w, h), Image::makeF(w, h)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
      const bool white = double(y) + 0.5 > slope * (double(x) + 0.5) + offset;
      // The area of the pixel above the line: the line's height within the
      // pixel integrated over its width (clamped to the pixel), in steps
      // fine enough to be exact to 1e-6.
      double covered = 0.0;
      constexpr int kSteps = 1000;
      for (int k = 0; k < kSteps; ++k) {
        const double lineY = slope * (double(x) + (double(k) + 0.5) / kSteps) + offset;
        covered += std::clamp(double(y + 1) - std::max(lineY, double(y)), 0.0, 1.0) / kSteps;
      }
      for (int c = 0; c < 3; ++c) {
        out.aliased.rgba8[i + size_t(c)] = white ? 255 : 0;
        out.exact.rgbaF[i + size_t(c)] = float(covered);
      }
      out.aliased.rgba8[i + 3] = 255;
      out.exact.rgbaF[i + 3] = 1.0f;
    }
  return out;
}

// Mean absolute difference of channel 0 to the exact coverage, over the
// pixels the edge passes through (exact coverage strictly inside (0, 1)).
double edgeError(const Image& img, const Image& exact) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < exact.pixelCount(); ++p) {
    const double c = exact.rgbaF[p * 4];
    if (c <= 1e-6 || c >= 1.0 - 1e-6) continue;
    sum += std::abs(double(img.rgba8[p * 4]) / 255.0 - c);
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

// Display values as floats, `factor`x`factor` boxes averaged (the
// supersampled reference: each pixel the mean of its subpixels).
std::vector<double> downsampled(const Image& big, int factor) {
  const int w = big.width / factor, h = big.height / factor;
  std::vector<double> out(size_t(w) * size_t(h) * 3, 0.0);
  for (int y = 0; y < big.height; ++y)
    for (int x = 0; x < big.width; ++x)
      for (int c = 0; c < 3; ++c)
        out[(size_t(y / factor) * size_t(w) + size_t(x / factor)) * 3 + size_t(c)] +=
            double(big.rgba8[(size_t(y) * size_t(big.width) + size_t(x)) * 4 + size_t(c)]) / 255.0 / (factor * factor);
  return out;
}

// Mean absolute difference to the reference over the pixels where the
// aliased frame is off by more than 2/255 (the edges), and their count.
double errorAtEdges(const Image& img, const Image& aliased, const std::vector<double>& ref, size_t* count = nullptr) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < img.pixelCount(); ++p) {
    bool edge = false;
    for (int c = 0; c < 3; ++c) edge = edge || std::abs(double(aliased.rgba8[p * 4 + size_t(c)]) / 255.0 - ref[p * 3 + size_t(c)]) > 2.0 / 255.0;
    if (!edge) continue;
    for (int c = 0; c < 3; ++c) sum += std::abs(double(img.rgba8[p * 4 + size_t(c)]) / 255.0 - ref[p * 3 + size_t(c)]) / 3.0;
    ++n;
  }
  if (count) *count = n;
  return n ? sum / double(n) : 0.0;
}


// The post tests' view turned about its axis by `rollDeg` (42°: the
// horizon a straight edge near 45°).
render::RenderView rolledView(int w, int h, double rollDeg) {
  render::RenderView v = test::postTestView(w, h);
  v.orientation = v.orientation * glm::angleAxis(glm::radians(rollDeg), glm::dvec3(0.0, 0.0, 1.0));
  return v;
}

}  // namespace

class TestSmaa : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // Straight edges at several slopes (shallow ones are long L and Z
  // patterns, the method's home ground): the twin's picture is far nearer
  // to the exact coverage than the aliased one.
  void straightEdgesApproachTheirCoverage() {
    // (slope, the share of the aliased error at most left): 45° is the
    // worst case, for any method (diagonalsNearFortyFiveDegrees).
    for (auto [slope, share] : {std::pair{0.1, 0.1}, std::pair{0.25, 0.3}, std::pair{0.4, 0.45},
                                std::pair{-0.2, 0.45}, std::pair{2.5, 0.45}, std::pair{1.0, 0.8}}) {
      const HalfPlane hp = halfPlane(96, 64, slope, slope < 0 ? 50.0 : 12.3);
      const double before = edgeError(hp.aliased, hp.exact);
      const double after = edgeError(test::smaaReference(hp.aliased), hp.exact);
      std::printf("slope %5.2f: mean error at the edge %.4f aliased, %.4f SMAA (%.2f)\n", slope, before, after,
                  after / before);
      QVERIFY2(before > 0.1, qPrintable(QString::number(before)));
      QVERIFY2(after < share * before, qPrintable(QString("%1 vs %2").arg(after).arg(before)));
    }
    // Flat colour and a vertical step with no crossing edges: unchanged.
    const HalfPlane flat = halfPlane(32, 32, 0.0, 100.0);
    QVERIFY(test::smaaReference(flat.aliased) == flat.aliased);
  }

  // At 45° every offset of the line in [0, 1) gives the same staircase, so
  // nothing that sees only the picture can tell where the line is. The
  // least mean error is then the median estimate, the line through the
  // steps' midpoints: a boundary pixel's exact coverage is c²/2 (c the
  // offset), the estimate 1/8, E|c²/2 - 1/8| = 1/8 against the aliased
  // E[c²/2] = 1/6 for c uniform: 0.75 of the aliased error is the floor for
  // any method. The twin reaches it (averaged over evenly spaced offsets).
  // Near 45° the diagonal patterns find the slope from the run's ends:
  // there they leave under 0.35 of the aliased error where the orthogonal
  // patterns alone leave over 0.45.
  void diagonalsNearFortyFiveDegrees() {
    for (double slope : {1.0, 0.8, 0.9, 1.1, 1.25, -0.9, -1.1}) {
      double before = 0.0, after = 0.0, orthogonal = 0.0;
      constexpr int kOffsets = 20;
      for (int k = 0; k < kOffsets; ++k) {
        const HalfPlane hp = halfPlane(96, 64, slope, (slope < 0 ? 60.0 : 12.0) + (double(k) + 0.5) / kOffsets);
        before += edgeError(hp.aliased, hp.exact) / kOffsets;
        after += edgeError(test::smaaReference(hp.aliased), hp.exact) / kOffsets;
        orthogonal += edgeError(test::smaaReference(hp.aliased, 0.1f, 16, false), hp.exact) / kOffsets;
      }
      std::printf("slope %5.2f over %d offsets: %.4f aliased, SMAA %.3f of it (%.3f orthogonal only)\n", slope, kOffsets,
                  before, after / before, orthogonal / before);
      if (slope == 1.0) {
        QVERIFY2(std::abs(before - 1.0 / 6.0) < 0.01, qPrintable(QString::number(before)));
        QVERIFY2(after / before > 0.73 && after / before < 0.78, qPrintable(QString::number(after / before)));
      } else {
        QVERIFY2(after / before < 0.35, qPrintable(QString("slope %1: %2").arg(slope).arg(after / before)));
        QVERIFY2(orthogonal / before > 0.45, qPrintable(QString("slope %1: %2").arg(slope).arg(orthogonal / before)));
      }
    }
  }

  // Rectangles, level and turned a little: their corners are real, where
  // MLAA's outlines would round them (a level rectangle came out worse
  // than aliased: 1.21 of its error). With the corner module the level one
  // is no worse than aliased, and both are nearer to their exact coverage
  // (16 x 16 samples a pixel) than without it.
  void rectanglesKeepTheirCorners() {
    for (double angle : {0.0, 3.0, 10.0}) {
      double aliased = 0.0, smaa = 0.0, noCorners = 0.0;
      for (int k = 0; k < 6; ++k) {
        const int w = 64, h = 64;
        const double cx = 32.3 + 0.13 * k, cy = 31.7 + 0.07 * k, hw = 9.5 + k, hh = 6.2 + 0.5 * k;
        const double c = std::cos(glm::radians(angle)), sn = std::sin(glm::radians(angle));
        const auto inside = [&](double x, double y) {
          const double u = (x - cx) * c + (y - cy) * sn, v = -(x - cx) * sn + (y - cy) * c;
          return std::abs(u) < hw && std::abs(v) < hh;
        };
        Image img = Image::make8(w, h);
        std::vector<double> exact(size_t(w) * size_t(h));
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const size_t i = size_t(h - 1 - y) * size_t(w) + size_t(x);
            for (int ch = 0; ch < 3; ++ch) img.rgba8[i * 4 + size_t(ch)] = inside(x + 0.5, y + 0.5) ? 255 : 0;
            img.rgba8[i * 4 + 3] = 255;
            int n = 0;
            for (int a = 0; a < 16; ++a)
              for (int b = 0; b < 16; ++b) n += inside(x + (a + 0.5) / 16.0, y + (b + 0.5) / 16.0) ? 1 : 0;
            exact[i] = n / 256.0;
          }
        const Image with = test::smaaReference(img), without = test::smaaReference(img, 0.1f, 16, true, false);
        for (size_t i = 0; i < exact.size(); ++i) {
          aliased += std::abs(img.rgba8[i * 4] / 255.0 - exact[i]);
          smaa += std::abs(with.rgba8[i * 4] / 255.0 - exact[i]);
          noCorners += std::abs(without.rgba8[i * 4] / 255.0 - exact[i]);
        }
      }
      std::printf("rectangles at %4.1f°: SMAA %.2f of the aliased error, %.2f without the corner module\n", angle,
                  smaa / aliased, noCorners / aliased);
      QVERIFY2(smaa < noCorners, qPrintable(QString("%1: %2 vs %3").arg(angle).arg(smaa).arg(noCorners)));
      if (angle == 0.0) QVERIFY2(smaa <= aliased, qPrintable(QString("%1 vs %2").arg(smaa).arg(aliased)));
      if (angle < 5.0) QVERIFY2(smaa < 0.85 * noCorners, qPrintable(QString("%1 vs %2").arg(smaa).arg(noCorners)));
    }
  }

  // Not chosen: no SMAA pass, no edge or weight texture (first, before
  // any frame with SMAA left textures of those names in the pool).
  void nothingWhenNotChosen() {
    scene::SceneState s = test::postTestScene();
    for (scene::Antialiasing aa : {scene::Antialiasing::None, scene::Antialiasing::Fxaa, scene::Antialiasing::Msaa4}) {
      s.settings.antialiasing = aa;
      render::FrameStats stats;
      r_.render(s, test::postTestView(), false, &stats);
      QVERIFY(!passRan(stats, "smaa"));
      const std::string held = test::allocationNamed(r_.renderer(), "smaa");
      QVERIFY2(held.empty(), held.c_str());
    }
  }

  // The renderer's three passes against the twin on the renderer's own
  // aliased picture of the post tests' scene, level and rolled 42° (the
  // horizon a straight edge near 45°: the diagonal patterns' case).
  void theRendererMatchesItsTwin_data() {
    QTest::addColumn<double>("rollDeg");
    QTest::newRow("level") << 0.0;
    QTest::newRow("rolled") << 42.0;
  }
  void theRendererMatchesItsTwin() {
    QFETCH(double, rollDeg);
    scene::SceneState s = test::postTestScene();
    s.settings.antialiasing = scene::Antialiasing::None;
    const render::RenderView v = rolledView(240, 136, rollDeg);
    const Image aliased = r_.render(s, v);
    s.settings.antialiasing = scene::Antialiasing::Smaa;
    render::FrameStats stats;
    const Image smaa = r_.render(s, v, false, &stats);
    QVERIFY(passRan(stats, "smaa_edges") && passRan(stats, "smaa_weights") && passRan(stats, "smaa_blend"));
    const Image twin = test::smaaReference(aliased);
    size_t off = 0, changed = 0;
    int worst = 0;
    for (size_t i = 0; i < smaa.rgba8.size(); ++i) {
      if (i % 4 == 3) continue;
      const int d = std::abs(int(smaa.rgba8[i]) - int(twin.rgba8[i]));
      worst = std::max(worst, d);
      off += d > 1 ? 1 : 0;
      changed += smaa.rgba8[i] != aliased.rgba8[i] ? 1 : 0;
    }
    const double channels = double(smaa.pixelCount()) * 3.0;
    std::printf("renderer vs twin: %zu of %.0f channels off by more than 1/255 (worst %d); %zu changed by SMAA\n", off,
                channels, worst, changed);
    QVERIFY2(double(off) <= 0.001 * channels, qPrintable(QString::number(off)));
    QVERIFY2(double(changed) >= 0.005 * channels, qPrintable(QString::number(changed)));
    // The rolled horizon takes the diagonal patterns: without them the
    // twin's picture is another.
    const Image orthogonal = test::smaaReference(aliased, 0.1f, 16, false);
    size_t byDiagonals = 0;
    for (size_t i = 0; i < smaa.rgba8.size(); ++i) byDiagonals += std::abs(int(smaa.rgba8[i]) - int(orthogonal.rgba8[i])) > 1;
    std::printf("%zu channels differ from the orthogonal patterns alone\n", byDiagonals);
    if (rollDeg != 0.0) QVERIFY2(byDiagonals >= 200, qPrintable(QString::number(byDiagonals)));
  }

  // Nearer to a 4x4 supersampled render of the same view than the aliased
  // frame, at the edges (FXAA's figure printed beside, not asserted).
  // Level and rolled 42° (the horizon near 45°: there the diagonal patterns
  // must bring the frame nearer than the orthogonal ones alone, the twin's
  // figure without them).
  void nearerToSupersampling_data() {
    QTest::addColumn<double>("rollDeg");
    QTest::newRow("level") << 0.0;
    QTest::newRow("rolled") << 42.0;
  }
  void nearerToSupersampling() {
    QFETCH(double, rollDeg);
    scene::SceneState s = test::postTestScene();
    const int w = 192, h = 108, factor = 4;
    const auto view = [rollDeg](int vw, int vh) { return rolledView(vw, vh, rollDeg); };
    s.settings.antialiasing = scene::Antialiasing::None;
    const std::vector<double> ref = downsampled(r_.render(s, view(w * factor, h * factor)), factor);
    const Image aliased = r_.render(s, view(w, h));
    s.settings.antialiasing = scene::Antialiasing::Smaa;
    const Image smaa = r_.render(s, view(w, h));
    s.settings.antialiasing = scene::Antialiasing::Fxaa;
    const Image fxaa = r_.render(s, view(w, h));
    size_t edges = 0;
    const double eNone = errorAtEdges(aliased, aliased, ref, &edges);
    const double eSmaa = errorAtEdges(smaa, aliased, ref), eFxaa = errorAtEdges(fxaa, aliased, ref);
    const double eOrthogonal = errorAtEdges(test::smaaReference(aliased, 0.1f, 16, false), aliased, ref);
    std::printf("against 4x4 supersampling, %zu edge pixels: none %.4f, SMAA %.4f (orthogonal only %.4f), FXAA %.4f\n",
                edges, eNone, eSmaa, eOrthogonal, eFxaa);
    QVERIFY(edges > 200);
    QVERIFY2(eSmaa < 0.85 * eNone, qPrintable(QString("%1 vs %2").arg(eSmaa).arg(eNone)));
    QVERIFY2(eSmaa <= eOrthogonal + 1e-4, qPrintable(QString("%1 vs %2").arg(eSmaa).arg(eOrthogonal)));
    if (rollDeg != 0.0) QVERIFY2(eSmaa < 0.95 * eOrthogonal, qPrintable(QString("%1 vs %2").arg(eSmaa).arg(eOrthogonal)));
  }

};

QTEST_GUILESS_MAIN(TestSmaa)
#include "test_smaa.moc"
