// Weighted Voronoi stippling (render/passes/stipple_passes.h,
// docs/rendering.md "Stylised effects"): the renderer against its CPU twin
// (the same steps with exact Voronoi cells instead of jump flooding) on
// the renderer's own picture, the tone following the picture's darkness,
// Lloyd relaxation approaching centroidal cells, the stiff cases (white,
// black, one-pixel views) and nothing when off; in a stereo pair the
// second eye's dots are the first eye's on the surfaces both see.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/stipple_layout.h"
#include "pass_stats.h"
#include "post_scene.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "stereo_plane.h"
#include "stipple_reference.h"

using namespace hs;
using test::passRan;

namespace {

double inkOf(const Image& img, size_t pixel) { return 1.0 - double(img.rgba8[pixel * 4]) / 255.0; }

double meanInk(const Image& img) {
  double sum = 0.0;
  for (size_t p = 0; p < img.pixelCount(); ++p) sum += inkOf(img, p);
  return sum / double(img.pixelCount());
}

// The post tests' scene two stops darker (more dots to compare).
scene::SceneState darkerScene() {
  scene::SceneState s = test::postTestScene();
  s.settings.exposureEv100 += 2.0f;
  return s;
}

scene::SceneState stippledScene(int iterations) {
  scene::SceneState s = darkerScene();
  s.settings.post.stipple = true;
  s.settings.post.stippleSpacingPx = 20.0f;  // 5 px at 270 rows
  s.settings.post.stippleDotPx = 5.0f;
  s.settings.post.stippleIterations = iterations;
  return s;
}

}  // namespace

class TestStipple : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // Off: no stippling pass, no grid, buffer or map in the registry (first,
  // before a frame with it left anything of those names in the pool).
  void nothingWhenOff() {
    scene::SceneState s = test::postTestScene();
    render::FrameStats stats;
    r_.render(s, test::postTestView(), false, &stats);
    QVERIFY(!passRan(stats, "stipple"));
    const std::string held = test::allocationNamed(r_.renderer(), "stipple");
    QVERIFY2(held.empty(), held.c_str());
  }

  // The renderer's dots against the twin's on the renderer's own picture:
  // the same dots but where jump flooding misassigned a cell (rare, and a
  // site that moved by it moves the dot a little), the same ink overall.
  void theRendererMatchesItsTwin() {
    const int w = 480, h = 270;
    const render::RenderView v = test::postTestView(w, h);
    const Image before = r_.render(darkerScene(), v);
    for (int iterations : {0, 8}) {
      const scene::SceneState s = stippledScene(iterations);
      render::FrameStats stats;
      const Image dots = r_.render(s, v, false, &stats);
      QVERIFY(passRan(stats, "stipple_density") && passRan(stats, "stipple_relax"));
      if (iterations == 0)  // no Lloyd step: no seeds or sums buffer (the first frame with stippling)
        for (const char* name : {"stipple_seeds", "stipple_sums"}) {
          const std::string held = test::allocationNamed(r_.renderer(), name);
          QVERIFY2(held.empty(), held.c_str());
        }
      const StippleLayout layout = stippleLayout(s.settings.post.stippleSpacingPx, s.settings.post.stippleDotPx, w, h);
      const test::StippleTwin twin = test::stippleTwin(before, layout, iterations);
      const Image ref = test::stippledPicture(twin, w, h);
      size_t off = 0;
      for (size_t p = 0; p < dots.pixelCount(); ++p) off += std::abs(inkOf(dots, p) - inkOf(ref, p)) > 8.0 / 255.0;
      const double share = double(off) / double(dots.pixelCount());
      std::printf("%d steps: %u candidates, ink %.4f renderer, %.4f twin; %.2f%% of pixels differ\n", iterations,
                  layout.candidates, meanInk(dots), meanInk(ref), 100.0 * share);
      QVERIFY2(share < (iterations == 0 ? 0.001 : 0.005), qPrintable(QString::number(share)));
      QVERIFY(std::abs(meanInk(dots) - meanInk(ref)) < 0.02 * meanInk(ref));
      QVERIFY(meanInk(dots) > 0.02);
    }
  }

  // The ink follows the picture: over blocks of 24 x 24 pixels the mean
  // ink rises with the darkness of the picture before (a strong
  // correlation), and where the picture is black the ink is what the
  // dots' area per spacing² promises.
  void theInkFollowsTheDarkness() {
    const int w = 480, h = 270, block = 24;
    const render::RenderView v = test::postTestView(w, h);
    const Image before = r_.render(darkerScene(), v);
    const Image dots = r_.render(stippledScene(8), v);
    std::vector<double> dark, ink;
    for (int by = 0; by + block <= h; by += block)
      for (int bx = 0; bx + block <= w; bx += block) {
        double d = 0.0, k = 0.0;
        for (int y = by; y < by + block; ++y)
          for (int x = bx; x < bx + block; ++x) {
            const size_t p = size_t(y) * size_t(w) + size_t(x);
            const uint8_t* c = &before.rgba8[p * 4];
            d += 1.0 - (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) / 255.0;
            k += inkOf(dots, p);
          }
        dark.push_back(d / (block * block));
        ink.push_back(k / (block * block));
      }
    double md = 0, mk = 0;
    for (size_t i = 0; i < dark.size(); ++i) md += dark[i], mk += ink[i];
    md /= double(dark.size());
    mk /= double(ink.size());
    double sdk = 0, sdd = 0, skk = 0;
    for (size_t i = 0; i < dark.size(); ++i) {
      sdk += (dark[i] - md) * (ink[i] - mk);
      sdd += (dark[i] - md) * (dark[i] - md);
      skk += (ink[i] - mk) * (ink[i] - mk);
    }
    const double correlation = sdk / std::sqrt(sdd * skk);
    std::printf("blocks: %zu, darkness-ink correlation %.3f\n", dark.size(), correlation);
    QVERIFY2(correlation > 0.85, qPrintable(QString::number(correlation)));
  }

  // Stiff pictures: white paper stays white (no candidate kept); black
  // keeps every candidate, the ink near a dot's area per spacing²; one-
  // and few-pixel views render.
  void whiteBlackAndTinyViews() {
    const int w = 320, h = 180;
    scene::SceneState s = stippledScene(8);
    s.settings.exposureEv100 = 30.0f;  // nothing lit enough to show: black
    const Image black = r_.render(s, test::postTestView(w, h));
    const StippleLayout layout = stippleLayout(s.settings.post.stippleSpacingPx, s.settings.post.stippleDotPx, w, h);
    // A dot's ink ramps from 1 to 0 over a pixel at its radius: its area is
    // pi (r² + 1/12).
    const double r = double(layout.radiusPx), spacing = 2.0 * double(layout.spacingCells);
    const double promised = 3.14159265 * (r * r + 1.0 / 12.0) / (spacing * spacing);
    std::printf("black: ink %.4f, pi (r^2 + 1/12) / spacing^2 = %.4f\n", meanInk(black), promised);
    QVERIFY2(meanInk(black) > 0.8 * promised && meanInk(black) < 1.05 * promised,
             qPrintable(QString::number(meanInk(black))));
    s.settings.exposureEv100 = -30.0f;  // everything burnt out: white
    s.settings.tonemap = scene::Tonemap::None;
    const Image white = r_.render(s, test::postTestView(w, h));
    QCOMPARE(meanInk(white), 0.0);
    s.settings.exposureEv100 = 8.0f;
    for (auto [tw, th] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{2, 5}, std::pair{7, 1}}) {
      const Image tiny = r_.render(s, test::postTestView(tw, th));
      QCOMPARE(tiny.width, tw);
      QCOMPARE(tiny.height, th);
    }
  }

  // Relaxation approaches a centroidal tessellation: the twin's sites'
  // mean distance to their cells' centroids falls with the steps (the
  // error the steps setting trades against time; bench_post times them).
  void relaxationApproachesCentroids() {
    const int w = 480, h = 270;
    const Image before = r_.render(darkerScene(), test::postTestView(w, h));
    const StippleLayout layout = stippleLayout(20.0f, 5.0f, w, h);
    double last = 1e9;
    std::vector<double> gaps;
    for (int steps : {0, 1, 2, 4, 8, 16}) {
      const double gap = test::stippleTwin(before, layout, steps).centroidGap;
      std::printf("%2d steps: mean distance to the centroid %.4f cells\n", steps, gap);
      QVERIFY2(gap < last, qPrintable(QString("%1 after %2").arg(gap).arg(last)));
      last = gap;
      gaps.push_back(gap);
    }
    QVERIFY(gaps.back() < 0.2 * gaps.front());
  }

  // The same frame twice is the same picture (integer sums: the atomics'
  // order does not matter).
  // A stereo pair: the second eye's dots are the first eye's, reprojected
  // by depth. On a plane facing both eyes at a distance chosen for a
  // disparity of exactly 10 pixels, the right eye's ink is the left's
  // moved by 10 pixels (the right eye rendered alone, with its own
  // screen-fixed candidates, matches no better than chance there); with a
  // box in front, the places only the right eye sees still get their
  // dots (the ink is the right eye's own within 5 %).
  void bothEyesSeeTheSameDotsOnASurface() {
    constexpr int disparity = 10;
    test::StereoPlane plane(disparity);
    scene::SceneState& s = plane.scene;
    s.settings.post.stipple = true;
    s.settings.post.stippleSpacingPx = 60.0f;  // 10 px at 180 rows
    s.settings.post.stippleDotPx = 15.0f;      // 2.5 px
    s.settings.post.stippleIterations = 6;
    const auto [l, r] = test::renderPair(r_, s, plane.left, plane.right);
    const int best = test::bestInkShift(l, r);
    const Image alone = r_.render(s, plane.right);
    qInfo("plane: best shift %d px (disparity %d), ink matched %.3f; the right eye alone: %.3f at the disparity",
          best, disparity, test::inkMatched(l, r, best), test::inkMatched(l, alone, disparity));
    QCOMPARE(best, disparity);
    QVERIFY(test::inkMatched(l, r, best) > 0.95);
    QVERIFY(test::inkMatched(l, alone, disparity) < 0.5);
    // A ball between the eyes and the plane: occluded dots dropped, the
    // disoccluded plane filled by the right eye's own candidates.
    plane.addBall();
    const auto [l2, r2] = test::renderPair(r_, s, plane.left, plane.right);
    const double inkPair = meanInk(r2), inkAlone = meanInk(r_.render(s, plane.right));
    qInfo("with a ball: the right eye's ink %.4f in the pair, %.4f alone", inkPair, inkAlone);
    QVERIFY(std::abs(inkPair - inkAlone) < 0.05 * inkAlone);
    QVERIFY(test::inkMatched(l2, r2, disparity) > 0.75);  // the plane's dots still shared
  }

  void deterministic() {
    const scene::SceneState s = stippledScene(6);
    const render::RenderView v = test::postTestView(320, 180);
    QVERIFY(r_.render(s, v) == r_.render(s, v));
  }
};

QTEST_MAIN(TestStipple)
#include "test_stipple.moc"
