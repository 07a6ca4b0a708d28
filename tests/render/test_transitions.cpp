// The stylised transitions between two shots (sequencer::Transition,
// shaders/group_combine.frag), on the demo scene's two views: at a quarter,
// half and three quarters of each, the combined HDR image against the CPU
// twin of the pattern applied to the two groups' own HDR images
// (tests/common/transition_reference.h); a golden strip per transition of
// the three points tone mapped; both eyes of a stereo pair get the same
// pattern; the glitch is the same in two runs and new every frame; the
// editor's stereo preview combines a transition's two shots.
#include <QtTest>

#include <cmath>

#include "render/offscreen_renderer.h"
#include "render/output_target.h"
#include "render/renderer.h"
#include "render/stereo_preview_renderer.h"
#include "render_golden.h"
#include "scene/demo_scene.h"
#include "transition_reference.h"
#include "two_shots.h"

using namespace hs;
using sequencer::Transition;

namespace {

constexpr Transition kPatterned[] = {Transition::CrossfadeBlur, Transition::Swipe,   Transition::WaterDrop,
                                     Transition::PixelDissolve, Transition::Glitch,  Transition::ZoomBlur,
                                     Transition::RadialWipe};
constexpr double kPoints[] = {0.25, 0.5, 0.75};

struct Difference {
  double mean = 0.0;     // over every channel of every pixel
  double share = 0.0;    // of pixels with a channel off by more than the tolerance
  double worst = 0.0;
};

// Relative to the pixel's brightness (HDR values reach tens in the sun).
Difference compare(const Image& a, const Image& b, double tol) {
  Difference d;
  if (a.rgbaF.size() != b.rgbaF.size() || a.rgbaF.empty()) return {INFINITY, 1.0, INFINITY};
  size_t off = 0;
  const size_t pixels = a.rgbaF.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    bool bad = false;
    for (int c = 0; c < 3; ++c) {
      const double x = a.rgbaF[p * 4 + c], y = b.rgbaF[p * 4 + c];
      const double e = std::abs(x - y) / std::max(1.0, std::abs(y));
      d.mean += e;
      d.worst = std::max(d.worst, e);
      bad = bad || e > tol;
    }
    off += bad ? 1 : 0;
  }
  d.mean /= double(pixels) * 3.0;
  d.share = double(off) / double(pixels);
  return d;
}

bool identical(const Image& a, const Image& b) { return a.rgbaF == b.rgbaF && a.rgba8 == b.rgba8; }

// Three images side by side (the golden strip).
Image strip(const std::vector<Image>& parts) {
  Image out;
  out.width = 0;
  out.height = parts.front().height;
  for (const Image& p : parts) out.width += p.width;
  out.rgba8.assign(size_t(out.width) * size_t(out.height) * 4, 0);
  int x0 = 0;
  for (const Image& p : parts) {
    for (int y = 0; y < p.height; ++y)
      std::copy_n(&p.rgba8[size_t(y) * size_t(p.width) * 4], size_t(p.width) * 4,
                  &out.rgba8[(size_t(y) * size_t(out.width) + size_t(x0)) * 4]);
    x0 += p.width;
  }
  return out;
}

}  // namespace

class TestTransitions : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  scene::SceneState demo_;
  render::RenderView a_, b_;

  // The combined HDR image and the two shots' own, of one transition frame.
  struct Frame {
    Image combined, from, to;
  };
  Frame render(Transition t, double p, int64_t frame, bool hdr = true) {
    render::GroupCombine pattern;
    pattern.transition = t;
    pattern.progress = float(p);
    pattern.frame = frame;
    Frame f;
    f.combined = r_.renderMix(demo_, {a_, b_}, {float(1.0 - p), float(p)}, hdr, nullptr, {}, &pattern);
    if (hdr) {
      f.from = r_.renderer().readHdr(0);
      f.to = r_.renderer().readHdr(1);
    }
    return f;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    std::optional<scene::SceneState> d = scene::buildDemoScene(error);
    QVERIFY2(d, error.c_str());
    demo_ = std::move(*d);
    demo_.settings.antialiasing = scene::Antialiasing::None;
    const auto cams = demo_.cameras();
    QVERIFY(!cams.empty());
    // 288 x 162: a sixth of 1080 rows, so the patterns' sizes (per 1080
    // rows) are whole pixels: blocks of 4, glitch bands of 2.
    a_ = render::viewFromCamera(demo_, cams.front(), 288, 162);
    b_ = test::otherSideOfTheValley(a_);
    r_.makeCurrent();
    r_.render(demo_, a_);  // the environment maps first, as every later frame finds them
  }

  void patternsMatchTheirCpuTwin_data() {
    QTest::addColumn<int>("kind");
    QTest::addColumn<double>("progress");
    for (Transition t : kPatterned)
      for (double p : kPoints)
        QTest::addRow("%s@%.2f", sequencer::transitionName(t), p) << int(t) << p;
  }
  void patternsMatchTheirCpuTwin() {
    QFETCH(int, kind);
    QFETCH(double, progress);
    const Transition t = Transition(kind);
    const Frame f = render(t, progress, 17);
    QVERIFY(!f.combined.rgbaF.empty() && !f.from.rgbaF.empty() && !f.to.rgbaF.empty());
    const Image ref = test::transitionReference(f.from, f.to, t, progress, 17);
    // Half floats (11 bits) and the GPU's 8-bit bilinear weights: 1 % of a
    // pixel's brightness, on all but a few pixels where a pattern's edge or
    // a threshold falls within rounding.
    const Difference d = compare(f.combined, ref, 0.01);
    qInfo("%s at %.2f: mean %.5f, off by > 1%%: %.3f%% of pixels, worst %.4f", sequencer::transitionName(t),
          progress, d.mean, 100.0 * d.share, d.worst);
    QVERIFY2(d.share <= 0.005, qPrintable(QString("%1% of pixels off").arg(100.0 * d.share)));
    QVERIFY2(d.mean <= 0.002, qPrintable(QString("mean %1").arg(d.mean)));
    // Not either shot alone: a pattern is drawn.
    QVERIFY(compare(f.combined, f.from, 0.01).share > 0.05);
    QVERIFY(compare(f.combined, f.to, 0.01).share > 0.05);
  }

  // A golden per transition: its quarter, half and three quarters side by
  // side, tone mapped as the film shows them.
  void goldenStrips_data() {
    QTest::addColumn<int>("kind");
    for (Transition t : kPatterned) QTest::addRow("%s", sequencer::transitionName(t)) << int(t);
  }
  void goldenStrips() {
    QFETCH(int, kind);
    const Transition t = Transition(kind);
    // At half the size of the checks above (the strips are kept in the repository).
    render::RenderView a = a_, b = b_;
    a.width = b.width = a_.width / 2;
    a.height = b.height = a_.height / 2;
    std::vector<Image> parts;
    for (double p : kPoints) {
      render::GroupCombine pattern;
      pattern.transition = t;
      pattern.progress = float(p);
      pattern.frame = 17;
      parts.push_back(r_.renderMix(demo_, {a, b}, {float(1.0 - p), float(p)}, false, nullptr, {}, &pattern));
    }
    test::verifyGolden(std::string("transition_") + sequencer::transitionName(t), strip(parts));
  }

  // Every eye of a stereo pair: the pattern at the same screen place, on
  // that eye's two shots.
  void bothEyesGetTheSamePattern() {
    render::OutputTarget outs[6];
    auto target = [&](int i, const render::RenderView& v, const char* name) {
      outs[i].ensure(v.width, v.height);
      return render::ViewTarget{v, outs[i].fbo(), name};
    };
    const render::RenderView al = test::shiftedSideways(a_, -0.03), ar = test::shiftedSideways(a_, 0.03);
    const render::RenderView bl = test::shiftedSideways(b_, -0.03), br = test::shiftedSideways(b_, 0.03);
    render::ViewGroup ga{{target(0, al, "left"), target(1, ar, "right")}, &a_};
    render::ViewGroup gb{{target(2, bl, "left"), target(3, br, "right")}, &b_};
    render::GroupCombine combine;
    combine.targets = {target(4, bl, "left"), target(5, br, "right")};
    combine.weights = {0.5f, 0.5f};
    combine.transition = Transition::Glitch;
    combine.progress = 0.5f;
    combine.frame = 3;
    render::RenderOptions o;
    o.keepHdr = true;
    r_.renderer().renderGroups(demo_, {ga, gb}, o, &combine);
    for (size_t eye = 0; eye < 2; ++eye) {
      const Image from = r_.renderer().readHdr(eye), to = r_.renderer().readHdr(2 + eye);
      const Image mixed = r_.renderer().readHdr(4 + eye);
      const Difference d = compare(mixed, test::transitionReference(from, to, Transition::Glitch, 0.5, 3), 0.01);
      qInfo("eye %zu: %.3f%% of pixels off", eye, 100.0 * d.share);
      QVERIFY(d.share <= 0.005);
    }
  }

  // The editor's stereo preview during the demo's crossfade: both shots
  // combined as the export combines them (between the two, neither); a
  // swipe there shows the incoming shot on the left, the outgoing on the
  // right, each as the preview shows it alone.
  void previewCombinesTheTwoShots() {
    const std::optional<sequencer::Shot> shot = sequencer::shotAt(demo_.sequence.cuts, 450);
    QVERIFY(shot && shot->incoming);
    const int w = 160, h = 90;
    // Without the demo's LUT and bloom, which are not monotonic per pixel
    // (a combined pixel between the shots' could map outside them).
    scene::SceneState s = demo_;
    s.settings.post.lutEnabled = false;
    s.settings.post.bloom = false;
    render::StereoPreviewRenderer preview;
    render::OutputTarget out;
    out.ensure(w, h);
    auto draw = [&](uint64_t camera, const render::PreviewTransition* t) {
      const render::StereoPreviewResult r = preview.draw(r_.renderer(), s, scene::EntityId(camera),
                                                         render::StereoPreviewMode::Left, double(w) / h, out.fbo(), w,
                                                         h, nullptr, t);
      return r.drawn ? r_.renderer().readDisplay(out.fbo(), w, h) : Image{};
    };
    const Image a = draw(shot->camera, nullptr), b = draw(shot->incoming, nullptr);
    render::PreviewTransition t{scene::EntityId(shot->incoming), *shot, 450};
    const Image mixed = draw(shot->camera, &t);
    QVERIFY(!a.rgba8.empty() && a.rgba8 != b.rgba8);
    QVERIFY(mixed.rgba8 != a.rgba8 && mixed.rgba8 != b.rgba8);
    int outside = 0;
    for (size_t i = 0; i < mixed.rgba8.size(); ++i) {
      if (i % 4 == 3) continue;
      const int lo = std::min(a.rgba8[i], b.rgba8[i]), hi = std::max(a.rgba8[i], b.rgba8[i]);
      outside += mixed.rgba8[i] < lo - 2 || mixed.rgba8[i] > hi + 2;
    }
    QVERIFY2(outside == 0, qPrintable(QString("%1 channels outside the two shots").arg(outside)));
    t.shot.transition = Transition::Swipe;
    t.shot.progress = 0.5;
    const Image swipe = draw(shot->camera, &t);
    int leftOff = 0, rightOff = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(c);
          if (x < int(0.4 * w)) leftOff = std::max(leftOff, std::abs(int(swipe.rgba8[i]) - int(b.rgba8[i])));
          if (x >= int(0.6 * w)) rightOff = std::max(rightOff, std::abs(int(swipe.rgba8[i]) - int(a.rgba8[i])));
        }
    QVERIFY2(leftOff <= 1 && rightOff <= 1, qPrintable(QString("left %1, right %2").arg(leftOff).arg(rightOff)));
    preview.release();
    out.release();
  }

  void glitchIsAFunctionOfTheFrame() {
    const Frame once = render(Transition::Glitch, 0.5, 40);
    const Frame again = render(Transition::Glitch, 0.5, 40);
    QVERIFY(identical(once.combined, again.combined));
    const Frame next = render(Transition::Glitch, 0.5, 41);
    QVERIFY(compare(next.combined, once.combined, 0.01).share > 0.05);
    // The dissolve's blocks depend on the progress alone.
    QVERIFY(identical(render(Transition::PixelDissolve, 0.4, 1).combined,
                      render(Transition::PixelDissolve, 0.4, 99).combined));
  }
};

QTEST_GUILESS_MAIN(TestTransitions)
#include "test_transitions.moc"
