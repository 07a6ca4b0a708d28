// The stylised effects (docs/rendering.md "Stylised effects";
// render/passes/stylised_passes.h) against their CPU twin
// (tests/common/stylised_reference.h) applied to the renderer's own image
// with the effects off: comic, outlines, CRT, Bayer and blue-noise
// dithering alone and together, the anisotropic Kuwahara filter, error
// diffusion (against the sequential scan). The editor's before/after split. Goldens
// per effect. Off costs nothing (no pass, no texture); the blue-noise map
// is blue (little low-frequency energy against white noise's) and holds
// every rank once; both eyes dither with the same screen pattern, and
// error diffusion's pattern sits on the surfaces in both eyes; a stiff Kuwahara (sharpness 16 on grain at
// full strength) stays finite and keeps the picture.
#include <QtTest>

#include <cmath>
#include <complex>
#include <random>

#include "pass_stats.h"
#include "core/blue_noise.h"
#include "render/offscreen_renderer.h"
#include "render/output_target.h"
#include "render/renderer.h"
#include "demo_once.h"
#include "render_golden.h"
#include "post_scene.h"
#include "stereo_plane.h"
#include "stylised_reference.h"
#include "two_shots.h"

using namespace hs;

namespace {

constexpr int kNoiseSide = 64;  // render/passes/stylised_passes.h kBlueNoiseSide

std::vector<float> thresholds() {
  const std::vector<uint32_t> ranks = blueNoiseRanks(kNoiseSide);
  std::vector<float> v(ranks.size());
  for (size_t i = 0; i < ranks.size(); ++i) v[i] = (float(ranks[i]) + 0.5f) / float(ranks.size());
  return v;
}

// Largest channel difference and the share of pixels more than `tol` off.
std::pair<int, double> compare8(const Image& a, const Image& b, int tol) {
  int worst = 0;
  size_t over = 0;
  const size_t pixels = a.rgba8.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgba8[p * 4 + c]) - int(b.rgba8[p * 4 + c])));
    worst = std::max(worst, d);
    over += d > tol;
  }
  return {worst, double(over) / double(std::max<size_t>(pixels, 1))};
}

using test::passRan;

// The share of a threshold map's spectral energy at the lowest
// frequencies (radius <= side / 8, the DC term left out).
double lowFrequencyShare(const std::vector<float>& map, int side) {
  double low = 0, all = 0, mean = 0;
  for (float v : map) mean += double(v);
  mean /= double(map.size());
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u) {
      if (u == 0 && v == 0) continue;
      std::complex<double> sum = 0;
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
          sum += (double(map[size_t(y * side + x)]) - mean) *
                 std::polar(1.0, -2.0 * M_PI * (double(u * x) + double(v * y)) / side);
      const double e = std::norm(sum);
      const int fu = std::min(u, side - u), fv = std::min(v, side - v);
      all += e;
      if (fu * fu + fv * fv <= (side / 8) * (side / 8)) low += e;
    }
  return low / all;
}

}  // namespace

namespace {
// The share of pixels that are ink (red under 128).
double inkShare(const Image& img) {
  size_t ink = 0;
  for (size_t p = 0; p < img.pixelCount(); ++p) ink += img.rgba8[p * 4] < 128;
  return double(ink) / double(std::max<size_t>(img.pixelCount(), 1));
}
}  // namespace

class TestStylised : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  scene::SceneState base_ = test::postTestScene();

  // The renderer's output with `post`'s stylised effects, and the same
  // frame without them.
  std::pair<Image, Image> withAndWithout(const scene::PostSettings& post, const render::RenderView& v,
                                         render::FrameStats* stats = nullptr) {
    scene::SceneState plain = base_, styled = base_;
    styled.settings.post = post;
    return {r_.render(styled, v, false, stats), r_.render(plain, v, false)};
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    base_.settings.tonemap = scene::Tonemap::Aces;
  }

  void blueNoiseIsBlue() {
    const std::vector<float> blue = thresholds();
    std::vector<float> white(blue.size());
    std::mt19937 rng(7);
    for (float& v : white) v = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    const double b = lowFrequencyShare(blue, kNoiseSide), w = lowFrequencyShare(white, kNoiseSide);
    qInfo("low-frequency energy: blue noise %.4f, white noise %.4f", b, w);
    QVERIFY(b < 0.25 * w);
    // Every rank once.
    std::vector<uint32_t> ranks = blueNoiseRanks(kNoiseSide);
    std::sort(ranks.begin(), ranks.end());
    for (size_t i = 0; i < ranks.size(); ++i) QCOMPARE(ranks[i], uint32_t(i));
    QVERIFY(blueNoiseRanks(kNoiseSide) == blueNoiseRanks(kNoiseSide));
  }

  void perPixelEffectsMatchTheCpu_data() {
    QTest::addColumn<int>("which");
    QTest::newRow("comic") << 0;
    QTest::newRow("outlines") << 1;
    QTest::newRow("crt") << 2;
    QTest::newRow("bayer") << 3;
    QTest::newRow("blue_noise") << 4;
    QTest::newRow("outlines_crt_bayer") << 5;
  }
  void perPixelEffectsMatchTheCpu() {
    QFETCH(int, which);
    scene::PostSettings post;
    switch (which) {
      case 0: post.comic = true, post.comicLevels = 4, post.comicDotPx = 30, post.outlineThreshold = 0.15f; break;
      case 1: post.outlines = true, post.outlineThreshold = 0.1f, post.outlineColor = {0.9f, 0.1f, 0.1f}; break;
      case 2: post.crt = true, post.crtCurvature = 0.12f, post.crtLinesPer1080 = 60, post.crtMask = 0.4f; break;
      case 3: post.dither = scene::DitherMode::Bayer, post.ditherLevels = 3; break;
      case 4: post.dither = scene::DitherMode::BlueNoise, post.ditherLevels = 4; break;
      default:
        post.outlines = true, post.crt = true, post.dither = scene::DitherMode::Bayer, post.ditherLevels = 6;
        break;
    }
    const render::RenderView v = test::postTestView(192, 108);
    render::FrameStats stats;
    const auto [styled, plain] = withAndWithout(post, v, &stats);
    QVERIFY(passRan(stats, "stylise"));
    const Image ref = test::stylisePassReference(plain, post, thresholds(), kNoiseSide);
    // A dither level is a whole step: a pixel whose value sits on a
    // threshold within float rounding may land a step apart; the rest
    // within 2/255 (the CRT's bilinear reads: the GPU's 8-bit weights).
    const auto [worst, over] = compare8(styled, ref, 2);
    qInfo("largest difference %d/255, %.3f%% of pixels more than 2 apart", worst, 100.0 * over);
    QVERIFY2(over <= 0.005, qPrintable(QString::number(100.0 * over) + "%"));
    // It did something (outlines touch the edges alone: a few percent).
    QVERIFY(compare8(styled, plain, 2).second > (which == 1 ? 0.005 : 0.05));
  }

  void kuwaharaMatchesTheCpu() {
    scene::PostSettings post;
    post.kuwahara = true;
    post.kuwaharaRadiusPx = 36.0f;  // 3.6 px at 108 rows
    post.kuwaharaSharpness = 8.0f;
    const render::RenderView v = test::postTestView(192, 108);
    render::FrameStats stats;
    const auto [styled, plain] = withAndWithout(post, v, &stats);
    QVERIFY(passRan(stats, "kuwahara_tensor") && passRan(stats, "kuwahara_orient") && passRan(stats, "kuwahara"));
    QVERIFY(!passRan(stats, "stylise"));
    const Image ref = test::kuwaharaReference(plain, 3.6, 8.0);
    // The tensor and orientation pass through half floats: an ellipse a
    // hair different moves a few sector means by a level or two.
    const auto [worst, over] = compare8(styled, ref, 3);
    qInfo("largest difference %d/255, %.3f%% of pixels more than 3 apart", worst, 100.0 * over);
    QVERIFY2(over <= 0.01, qPrintable(QString::number(100.0 * over) + "%"));
    QVERIFY(compare8(styled, plain, 2).second > 0.05);
  }

  // Floyd-Steinberg on the GPU (a wavefront of rows in one workgroup)
  // against the sequential scan on the CPU; only the levels asked for;
  // the local mean kept (what error diffusion is for); the same in two runs.
  void errorDiffusionMatchesTheScan() {
    scene::PostSettings post;
    post.dither = scene::DitherMode::ErrorDiffusion;
    post.ditherLevels = 2;
    // Taller than a workgroup's band of 256 rows: bands hand over.
    const render::RenderView v = test::postTestView(320, 300);
    render::FrameStats stats;
    const auto [styled, plain] = withAndWithout(post, v, &stats);
    QVERIFY(passRan(stats, "error_diffusion") && passRan(stats, "dither_copy") && !passRan(stats, "stylise"));
    for (size_t i = 0; i < styled.rgba8.size(); ++i)
      if (i % 4 != 3) QVERIFY2(styled.rgba8[i] == 0 || styled.rgba8[i] == 255, "two levels only");
    const Image ref = test::errorDiffusionReference(plain, 2);
    // The same arithmetic in the same order, but error diffusion is
    // chaotic: where a value sits on the threshold within the GPU's
    // rounding (a fused multiply-add), one pixel flips and the errors
    // after it differ. So: identical for the first rows of the scan (a
    // different algorithm would differ within a few pixels), and a small
    // share overall.
    int firstRow = v.height;
    for (int gy = 0; gy < v.height && firstRow == v.height; ++gy)
      for (int x = 0; x < v.width; ++x) {
        const size_t i = (size_t(v.height - 1 - gy) * size_t(v.width) + size_t(x)) * 4;
        if (styled.rgba8[i] != ref.rgba8[i] || styled.rgba8[i + 1] != ref.rgba8[i + 1] ||
            styled.rgba8[i + 2] != ref.rgba8[i + 2]) {
          firstRow = gy;
          break;
        }
      }
    const auto [worst, over] = compare8(styled, ref, 2);
    qInfo("against the sequential scan: identical for the first %d of %d rows, %.3f%% of pixels differ", firstRow,
          v.height, 100.0 * over);
    QVERIFY(firstRow >= 16);
    QVERIFY2(over <= 0.10, qPrintable(QString::number(100.0 * over) + "%"));
    // The mean over 8 x 8 blocks kept within a few percent.
    double worstBlock = 0.0, sum = 0.0;
    int blocks = 0;
    for (int by = 0; by + 8 <= v.height; by += 8)
      for (int bx = 0; bx + 8 <= v.width; bx += 8) {
        double a = 0.0, b = 0.0;
        for (int y = by; y < by + 8; ++y)
          for (int x = bx; x < bx + 8; ++x)
            for (int c = 0; c < 3; ++c) {
              const size_t i = (size_t(y) * size_t(v.width) + size_t(x)) * 4 + size_t(c);
              a += styled.rgba8[i], b += plain.rgba8[i];
            }
        const double d = std::abs(a - b) / (64.0 * 3.0 * 255.0);
        worstBlock = std::max(worstBlock, d);
        sum += d;
        ++blocks;
      }
    qInfo("8x8 block means: mean difference %.4f, worst %.4f", sum / blocks, worstBlock);
    QVERIFY(sum / blocks < 0.03);
    scene::SceneState s = base_;
    s.settings.post = post;
    QVERIFY(r_.render(s, v).rgba8 == styled.rgba8);
  }

  // The editor's before/after split: the left half is the frame without
  // its effects, the right half the frame with them, a line between.
  void beforeAfterSplit() {
    const render::RenderView v = test::postTestView(192, 108);
    scene::SceneState s = base_;
    s.settings.post.comic = true;
    s.settings.post.vignette = true;
    render::RenderOptions o;
    o.postSplit = 0.5f;
    render::FrameStats stats;
    const Image split = r_.render(s, v, false, &stats, o);
    QVERIFY(passRan(stats, "post_before") && passRan(stats, "post_split"));
    const Image after = r_.render(s, v);
    const Image before = r_.render(base_, v);
    int leftOff = 0, rightOff = 0;
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t i = (size_t(y) * size_t(v.width) + size_t(x)) * 4 + size_t(c);
          if (x < 94) leftOff = std::max(leftOff, std::abs(int(split.rgba8[i]) - int(before.rgba8[i])));
          if (x > 97) rightOff = std::max(rightOff, std::abs(int(split.rgba8[i]) - int(after.rgba8[i])));
        }
    QCOMPARE(leftOff, 0);
    QCOMPARE(rightOff, 0);
    QVERIFY(before.rgba8 != after.rgba8);
    // Nothing to compare without effects: no extra pass, the same frame.
    const Image plain = r_.render(base_, v, false, &stats, o);
    QVERIFY(!passRan(stats, "post_split") && plain.rgba8 == before.rgba8);
  }

  // Sharpness 16 (the field's largest) on full-strength grain: every
  // sector's variance large, the weights small but not zero; the image
  // stays the picture (not black, not NaN turned black) and smooths the
  // grain.
  void stiffKuwaharaStaysFinite() {
    scene::SceneState s = base_;
    s.settings.post.grain = true;
    s.settings.post.grainIntensity = 1.0f;
    const render::RenderView v = test::postTestView(192, 108);
    const Image grainy = r_.render(s, v);
    s.settings.post.kuwahara = true;
    s.settings.post.kuwaharaRadiusPx = 60.0f;
    s.settings.post.kuwaharaSharpness = 16.0f;
    const Image painted = r_.render(s, v);
    auto black = [](const Image& img) {
      size_t n = 0;
      for (size_t p = 0; p < img.rgba8.size(); p += 4) n += img.rgba8[p] + img.rgba8[p + 1] + img.rgba8[p + 2] == 0;
      return n;
    };
    QVERIFY2(black(painted) <= black(grainy), qPrintable(QString("%1 black pixels, %2 before").arg(black(painted)).arg(black(grainy))));
    // Smoother: the mean absolute difference between horizontal neighbours drops.
    auto roughness = [](const Image& img) {
      double sum = 0;
      for (int y = 0; y < img.height; ++y)
        for (int x = 1; x < img.width; ++x)
          for (int c = 0; c < 3; ++c)
            sum += std::abs(int(img.rgba8[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + size_t(c)]) -
                            int(img.rgba8[(size_t(y) * size_t(img.width) + size_t(x) - 1) * 4 + size_t(c)]));
      return sum;
    };
    qInfo("roughness: grain %.0f, painted %.0f", roughness(grainy), roughness(painted));
    QVERIFY(roughness(painted) < 0.5 * roughness(grainy));
  }

  void offCostsNothing() {
    scene::SceneState s = base_;
    s.settings.post.outlineThreshold = 0.7f;  // parameters of disabled effects change nothing
    s.settings.post.ditherLevels = 3;
    s.settings.post.crtCurvature = 0.4f;
    // A renderer of its own: the pool keeps what earlier frames made.
    render::OffscreenRenderer fresh;
    std::string error;
    QVERIFY2(fresh.initialize(error), error.c_str());
    render::FrameStats stats;
    const Image a = fresh.render(s, test::postTestView(), false, &stats);
    const Image b = fresh.render(base_, test::postTestView());
    QVERIFY(a.rgba8 == b.rgba8);
    for (const char* pass : {"stylise", "kuwahara", "blue_noise"}) QVERIFY2(!passRan(stats, pass), pass);
    for (const char* name : {"ldr_color", "kuwahara", "blue_noise"}) {
      const std::string held = test::allocationNamed(fresh.renderer(), name);
      QVERIFY2(held.empty(), held.c_str());
    }
    r_.makeCurrent();
  }

  // Error diffusion in a stereo pair: the second eye takes the first eye's
  // levels where it sees the same surface and diffuses its own error, so a
  // plane at a disparity of 10 pixels shows the left eye's pattern moved by
  // 10 pixels in the right eye (rendered alone, the right eye's pattern is
  // its own), with the right eye's tone kept, a ball in front included.
  void errorDiffusionFollowsTheSurfacesInStereo() {
    constexpr int disparity = 10;
    test::StereoPlane plane(disparity, glm::vec3(0.06f));
    scene::SceneState& s = plane.scene;
    s.settings.post.dither = scene::DitherMode::ErrorDiffusion;
    s.settings.post.ditherLevels = 2;
    const auto [l, r] = test::renderPair(r_, s, plane.left, plane.right);
    const Image alone = r_.render(s, plane.right);
    const int best = test::bestInkShift(l, r);
    qInfo("plane: best shift %d px (disparity %d), ink matched %.3f; the right eye alone: %.3f at the disparity; "
          "ink %.4f in the pair, %.4f alone",
          best, disparity, test::inkMatched(l, r, best), test::inkMatched(l, alone, disparity), inkShare(r),
          inkShare(alone));
    QCOMPARE(best, disparity);
    QVERIFY(test::inkMatched(l, r, best) > 0.95);
    QVERIFY(test::inkMatched(l, alone, disparity) < 0.8);  // chance: the ink's share, 0.73
    QVERIFY(std::abs(inkShare(r) - inkShare(alone)) < 0.02 * inkShare(alone));
    plane.addBall();
    const auto [l2, r2] = test::renderPair(r_, s, plane.left, plane.right);
    const double pair = inkShare(r2), own = inkShare(r_.render(s, plane.right));
    qInfo("with a ball: the right eye's ink %.4f in the pair, %.4f alone", pair, own);
    QVERIFY(std::abs(pair - own) < 0.03 * own);
    QVERIFY(test::inkMatched(l2, r2, disparity) > 0.75);
    r_.makeCurrent();
  }

  // Both eyes of a pair dither with the same pattern at the same screen
  // place: each eye's image is its plain image through the one reference.
  void bothEyesDitherAlike() {
    const render::RenderView v = test::postTestView(128, 72);
    const render::RenderView left = test::shiftedSideways(v, -0.05), right = test::shiftedSideways(v, 0.05);
    r_.makeCurrent();
    render::OutputTarget outs[2];
    std::vector<render::ViewTarget> targets;
    for (int i = 0; i < 2; ++i) {
      outs[i].ensure(v.width, v.height);
      targets.push_back({i ? right : left, outs[i].fbo(), i ? "right" : "left"});
    }
    auto eyes = [&](const scene::SceneState& s) {
      r_.renderer().renderViews(s, targets);
      return std::pair{r_.renderer().readDisplay(outs[0].fbo(), v.width, v.height),
                       r_.renderer().readDisplay(outs[1].fbo(), v.width, v.height)};
    };
    scene::SceneState s = base_;
    const auto [plainL, plainR] = eyes(s);
    s.settings.post.dither = scene::DitherMode::BlueNoise;
    s.settings.post.ditherLevels = 2;
    const auto [l, r] = eyes(s);
    QVERIFY(plainL.rgba8 != plainR.rgba8);
    for (const auto& [styled, plain] : {std::pair{&l, &plainL}, std::pair{&r, &plainR}}) {
      const auto [worst, over] = compare8(*styled, test::stylisePassReference(*plain, s.settings.post, thresholds(), kNoiseSide), 2);
      QVERIFY2(over <= 0.005, qPrintable(QString::number(100.0 * over) + "%"));
    }
  }

  void goldens_data() {
    QTest::addColumn<int>("which");
    QTest::newRow("comic") << 0;
    QTest::newRow("outlines") << 1;
    QTest::newRow("crt") << 2;
    QTest::newRow("dither_bayer") << 3;
    QTest::newRow("dither_blue_noise") << 4;
    QTest::newRow("kuwahara") << 5;
    QTest::newRow("stipple") << 6;
  }
  // On the demo scene (terrain, trees, water, figures: every kind of edge and shade).
  void goldens() {
    QFETCH(int, which);
    const scene::SceneState* demo = test::demoOnce();
    QVERIFY(demo);
    scene::SceneState s = *demo;
    s.settings.antialiasing = scene::Antialiasing::None;
    scene::PostSettings& p = s.settings.post;
    switch (which) {
      case 0: p.comic = true; break;
      case 1: p.outlines = true; break;
      case 2: p.crt = true; break;
      case 3: p.dither = scene::DitherMode::Bayer; break;
      case 4: p.dither = scene::DitherMode::BlueNoise; break;
      case 5: p.kuwahara = true; break;
      default: p.stipple = true; break;
    }
    const render::RenderView v = render::viewFromCamera(s, s.cameras().front(), 256, 144);
    test::verifyGolden(std::string("stylised_") + QTest::currentDataTag(), r_.render(s, v));
  }
};

QTEST_GUILESS_MAIN(TestStylised)
#include "test_stylised.moc"
