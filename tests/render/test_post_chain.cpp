// The post chain (docs/rendering.md "Post-processing"; render/passes/
// output_passes.h, bloom_passes.h, shaders/tonemap.frag) against a CPU
// reference of its arithmetic (tests/common/post_reference.h) applied to
// the renderer's own HDR image: every tone map (none, ACES, AgX, PBR
// Neutral), the grade, the vignette, chromatic aberration and grain, alone
// and together, within 2/255. With every effect off the chain is the tone
// map alone (no other pass, no texture) and its image does not change when
// the disabled effects' parameters do. Grain follows the frame number and
// is the same in both eyes; bloom spreads a highlight's light symmetrically,
// further with a larger radius, and costs nothing when off. A golden per
// effect (and per tone map) on the demo.
#include <QtTest>

#include <cmath>

#include "pass_stats.h"
#include "mesh/primitives.h"
#include "render/auto_exposure.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "look_from.h"
#include "demo_once.h"
#include "render_golden.h"
#include "post_reference.h"
#include "post_scene.h"
#include "scene_parts.h"

using namespace hs;

namespace {

scene::SceneState hdrScene() { return test::postTestScene(); }
render::RenderView view(int w = 192, int h = 108) { return test::postTestView(w, h); }

using test::passRan;

// Largest channel difference and the share of channels more than 1 apart.
std::pair<int, double> compare8(const Image& a, const Image& b) {
  int worst = 0;
  size_t over = 0, n = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) {
    if (i % 4 == 3) continue;
    const int d = std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
    worst = std::max(worst, d);
    over += d > 1;
    ++n;
  }
  return {worst, double(over) / double(std::max<size_t>(n, 1))};
}

double luminanceAt(const Image& img, int x, int y) {
  const size_t i = (size_t(y) * size_t(img.width) + size_t(x)) * 4;
  return 0.2126 * img.rgba8[i] + 0.7152 * img.rgba8[i + 1] + 0.0722 * img.rgba8[i + 2];
}

}  // namespace

class TestPostChain : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

  // The renderer's output for `s` against the CPU reference on its HDR image.
  bool matchesTheReference(const scene::SceneState& s, const char* what, const render::RenderView& v = view()) {
    const Image hdr = r_.render(s, v, true);
    const Image out = r_.render(s, v, false);
    const Image ref = test::postReference(hdr, s.settings, s.time.frame);
    const auto [worst, over] = compare8(out, ref);
    qInfo("%s: largest difference %d/255, %.3f%% of the channels more than 1 apart", what, worst, 100.0 * over);
    return worst <= 2 && over < 0.01;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void everyToneMapMatchesTheCpu() {
    for (auto t : {scene::Tonemap::None, scene::Tonemap::Aces, scene::Tonemap::AgX, scene::Tonemap::PbrNeutral}) {
      scene::SceneState s = hdrScene();
      s.settings.tonemap = t;
      QVERIFY2(matchesTheReference(s, ("tone map " + std::to_string(int(t))).c_str()), "tone map");
    }
    // The curves differ where they should: highlights.
    scene::SceneState a = hdrScene(), b = hdrScene();
    a.settings.tonemap = scene::Tonemap::AgX;
    b.settings.tonemap = scene::Tonemap::PbrNeutral;
    QVERIFY(compare8(r_.render(a, view()), r_.render(b, view())).first > 20);
  }

  void eachEffectMatchesTheCpu() {
    struct Case {
      const char* name;
      void (*set)(scene::PostSettings&);
    };
    const Case cases[] = {
        {"grade", [](scene::PostSettings& p) {
           p.grade = true;
           p.temperature = 0.4f, p.tint = -0.2f;
           p.lift = {0.03f, 0.0f, 0.01f}, p.gamma = {1.1f, 1.0f, 0.9f}, p.gain = {1.1f, 1.0f, 0.95f};
           p.saturation = 1.3f;
         }},
        {"vignette", [](scene::PostSettings& p) { p.vignette = true, p.vignetteIntensity = 0.6f; }},
        {"chromatic aberration", [](scene::PostSettings& p) {
           p.chromaticAberration = true, p.chromaticAberrationPx = 6.0f;
         }},
        {"grain", [](scene::PostSettings& p) { p.grain = true, p.grainIntensity = 0.2f, p.grainSizePx = 3.0f; }},
        {"all together", [](scene::PostSettings& p) {
           p.grade = true, p.saturation = 0.7f, p.temperature = -0.3f;
           p.vignette = true, p.chromaticAberration = true, p.grain = true;
         }},
    };
    for (const Case& c : cases) {
      scene::SceneState s = hdrScene();
      s.settings.tonemap = scene::Tonemap::AgX;
      s.time.frame = 77;
      c.set(s.settings.post);
      QVERIFY2(matchesTheReference(s, c.name), c.name);
      // And it did something.
      QVERIFY2(compare8(r_.render(s, view()), r_.render(hdrScene(), view())).first > 4, c.name);
    }
  }

  // Off: the tone map pass alone, whatever the disabled effects hold.
  void chainOffIsTheToneMapAlone() {
    scene::SceneState s = hdrScene();
    render::FrameStats stats;
    const Image plain = r_.render(s, view(), false, &stats);
    QVERIFY(passRan(stats, "tonemap"));
    QVERIFY(!passRan(stats, "bloom"));
    scene::PostSettings& p = s.settings.post;
    p.bloomIntensity = 3.0f, p.saturation = 0.0f, p.gain = glm::vec3(4.0f), p.vignetteIntensity = 1.0f;
    p.grainIntensity = 1.0f, p.chromaticAberrationPx = 30.0f, p.temperature = 1.0f;
    const Image disabled = r_.render(s, view(), false, &stats);
    QVERIFY(plain.rgba8 == disabled.rgba8);
    QVERIFY(!passRan(stats, "bloom"));
    size_t passes = 0;
    for (const render::PassStats& ps : stats.passes) passes += ps.name.find("tonemap") != std::string::npos;
    QCOMPARE(passes, size_t(1));
    // Enabled with nothing to do: no pass either.
    p.bloom = true;
    p.bloomIntensity = 0.0f;
    r_.render(s, view(), false, &stats);
    QVERIFY(!passRan(stats, "bloom"));
  }

  // Grain: a function of the frame number, the same pattern in both eyes.
  void grainFollowsTheFrameAndBothEyesShareIt() {
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.tonemap = scene::Tonemap::None;
    s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = glm::vec3(0.2f);
    s.settings.exposureEv100 = float(scene::kReferenceEv100);
    s.settings.post.grain = true;
    s.settings.post.grainIntensity = 0.3f;
    s.time.frame = 10;
    render::RenderView left = view(), right = view();
    left.eye.x -= 0.03, right.eye.x += 0.03;  // a uniform sky: the eyes see the same light
    const Image l = r_.render(s, left), r = r_.render(s, right), again = r_.render(s, left);
    QVERIFY(l.rgba8 == again.rgba8);  // a pure function of the frame
    QVERIFY(l.rgba8 == r.rgba8);      // the same pattern in both eyes
    s.time.frame = 11;
    QVERIFY(compare8(r_.render(s, left), l).first > 4);  // the next frame's grain
    s.settings.post.grain = false;
    QVERIFY(compare8(r_.render(s, left), l).first > 4);
  }

  // Bloom: the lamp's light spread around it, left and right alike, further
  // with a larger radius; its passes and levels only when on.
  void bloomSpreadsHighlightsSymmetrically() {
    scene::SceneState s = hdrScene();
    s.settings.skyZenith = s.settings.skyHorizon = glm::vec3(0.0f);
    s.settings.tonemap = scene::Tonemap::AgX;
    const render::RenderView v = view(256, 144);
    const Image off = r_.render(s, v);
    s.settings.post.bloom = true;
    s.settings.post.bloomIntensity = 0.3f;
    s.settings.post.bloomThreshold = 1.0f;
    s.settings.post.bloomRadius = 0.5f;
    render::FrameStats stats;
    const Image on = r_.render(s, v, false, &stats);
    QVERIFY(passRan(stats, "bloom_down0") && passRan(stats, "bloom_up0"));
    s.settings.post.bloomRadius = 1.0f;
    const Image wide = r_.render(s, v);
    // The lamp's pixel (the brightest of the image without bloom).
    int lx = 0, ly = 0;
    double best = -1.0;
    for (int y = 0; y < off.height; ++y)
      for (int x = 0; x < off.width; ++x)
        if (luminanceAt(off, x, y) > best) best = luminanceAt(off, x, y), lx = x, ly = y;
    // Around it, 12 px away (off the lamp): brighter with bloom, about as
    // much left as right, more with the wider radius.
    const int d = 12;
    QVERIFY(lx - d >= 0 && lx + d < off.width);
    const double gainL = luminanceAt(on, lx - d, ly) - luminanceAt(off, lx - d, ly);
    const double gainR = luminanceAt(on, lx + d, ly) - luminanceAt(off, lx + d, ly);
    const double wideL = luminanceAt(wide, lx - d, ly) - luminanceAt(off, lx - d, ly);
    qInfo("bloom 12 px from the lamp: +%.1f left, +%.1f right; radius 1: +%.1f", gainL, gainR, wideL);
    QVERIFY(gainL > 3.0 && gainR > 3.0);
    QVERIFY(std::abs(gainL - gainR) < 0.35 * std::max(gainL, gainR));
    QVERIFY(wideL > gainL);
  }

  // A golden per effect of the chain on the demo scene (its own bloom, grade
  // and LUT turned off first, so each image shows one effect): the tone
  // maps, bloom, chromatic aberration, the grade, the demo's LUT, the
  // vignette, grain at frame 7 and automatic exposure. The CPU-reference
  // tests above check the arithmetic; these catch a change in the look.
  void goldens_data() {
    QTest::addColumn<int>("which");
    const char* names[] = {"tonemap_none", "tonemap_aces", "tonemap_agx", "tonemap_pbr_neutral", "bloom",
                           "chromatic_aberration", "grade", "lut", "vignette", "grain", "auto_exposure"};
    for (int i = 0; i < int(std::size(names)); ++i) QTest::newRow(names[i]) << i;
  }
  void goldens() {
    QFETCH(int, which);
    const scene::SceneState* demo = test::demoOnce();
    QVERIFY(demo);
    scene::SceneState s = *demo;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.tonemap = scene::Tonemap::Aces;
    const scene::LutData lut = s.settings.post.lut;
    scene::PostSettings& p = s.settings.post;
    p = scene::PostSettings{};
    switch (which) {
      case 0: s.settings.tonemap = scene::Tonemap::None; break;
      case 1: break;
      case 2: s.settings.tonemap = scene::Tonemap::AgX; break;
      case 3: s.settings.tonemap = scene::Tonemap::PbrNeutral; break;
      case 4: p.bloom = true, p.bloomIntensity = 0.1f; break;
      case 5: p.chromaticAberration = true, p.chromaticAberrationPx = 4.0f; break;
      case 6:
        p.grade = true, p.temperature = 0.3f, p.saturation = 1.3f;
        p.lift = {0.02f, 0.0f, 0.03f}, p.gain = {1.1f, 1.0f, 0.9f};
        break;
      case 7:
        QVERIFY(!lut.empty());
        p.lut = lut, p.lutEnabled = true;
        break;
      case 8: p.vignette = true, p.vignetteIntensity = 0.5f; break;
      case 9: p.grain = true, p.grainIntensity = 0.15f, s.time.frame = 7; break;
      default: p.autoExposure = true; break;
    }
    const render::RenderView v = render::viewFromCamera(s, s.cameras().front(), 256, 144);
    if (p.autoExposure) {
      render::AutoExposure ae;
      s.settings.exposureEv100 = float(ae.viewEv100(r_.renderer(), s, v));
      ae.release();
    }
    test::verifyGolden(std::string("post_") + QTest::currentDataTag(), r_.render(s, v));
  }
};

QTEST_MAIN(TestPostChain)
#include "test_post_chain.moc"
