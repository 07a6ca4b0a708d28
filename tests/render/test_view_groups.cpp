// View groups (Renderer::renderGroups): two cameras in one frame, each
// with its own visible set, levels of detail, shadows and light grid. On
// the demo scene (meshes, CDLOD terrain, sun shadows, lamps, glass):
// each group of a two-group frame has the same pixels as a frame rendered
// with that camera (or stereo pair) alone; the combined image is the
// weighted sum of the two, tone mapped (against the CPU's sum of the
// groups' own HDR images); the second group's passes carry its name.
#include <QtTest>

#include <cmath>

#include "render/offscreen_renderer.h"
#include "render/output_target.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "two_shots.h"

using namespace hs;

namespace {

double maxDifference(const Image& a, const Image& b) {
  if (a.rgbaF.size() != b.rgbaF.size() || a.rgbaF.empty()) return INFINITY;
  double worst = 0.0;
  for (size_t i = 0; i < a.rgbaF.size(); ++i) worst = std::max(worst, std::abs(double(a.rgbaF[i]) - double(b.rgbaF[i])));
  return worst;
}

}  // namespace

class TestViewGroups : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  scene::SceneState demo_;
  render::OutputTarget targets_[4];
  render::RenderView a_, b_;

  render::ViewTarget target(int i, const render::RenderView& v, const std::string& name = {}) {
    targets_[i].ensure(v.width, v.height);
    return {v, targets_[i].fbo(), name};
  }

  // One frame of `views` alone; their HDR images.
  std::vector<Image> alone(const std::vector<render::RenderView>& views) {
    std::vector<render::ViewTarget> t;
    for (size_t i = 0; i < views.size(); ++i) t.push_back(target(int(i), views[i], views.size() > 1 ? (i ? "right" : "left") : ""));
    render::RenderOptions o;
    o.keepHdr = true;
    r_.renderer().renderViews(demo_, t, o);
    std::vector<Image> out;
    for (size_t i = 0; i < views.size(); ++i) out.push_back(r_.renderer().readHdr(i));
    return out;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    std::optional<scene::SceneState> d = scene::buildDemoScene(error);
    QVERIFY2(d, error.c_str());
    demo_ = std::move(*d);
    const auto cams = demo_.cameras();
    QVERIFY(!cams.empty());
    a_ = render::viewFromCamera(demo_, cams.front(), 192, 108);
    b_ = test::otherSideOfTheValley(a_);
    r_.makeCurrent();
    // One frame first: the environment pass runs when the sky changed, so
    // the frames compared below all start from the same maps.
    alone({a_});
  }

  void eachGroupMatchesItsCameraAlone() {
    const Image aAlone = alone({a_})[0];
    // One frame: group 0 the mono shot, group 1 a stereo pair.
    render::ViewGroup ga{{target(0, a_)}, nullptr};
    const render::RenderView bl = test::shiftedSideways(b_, -0.03), br = test::shiftedSideways(b_, 0.03);
    render::ViewGroup gb{{target(1, bl, "left"), target(2, br, "right")}, &b_};
    render::RenderOptions o;
    o.keepHdr = true;
    o.passTimings = true;
    const std::vector<render::FrameStats> stats = r_.renderer().renderGroups(demo_, {ga, gb}, o);
    QCOMPARE(stats.size(), size_t(2));
    const Image ga0 = r_.renderer().readHdr(0), gb0 = r_.renderer().readHdr(1), gb1 = r_.renderer().readHdr(2);
    QCOMPARE(maxDifference(ga0, aAlone), 0.0);
    // The pair alone, its levels chosen from b_ (the pair's centre) as the
    // group's are, which is what a stereo export does.
    render::RenderOptions centred;
    centred.keepHdr = true;
    centred.lodView = &b_;
    r_.renderer().renderViews(demo_, {target(1, bl, "left"), target(2, br, "right")}, centred);
    const Image bl0 = r_.renderer().readHdr(0), br0 = r_.renderer().readHdr(1);
    QCOMPARE(maxDifference(gb0, bl0), 0.0);
    QCOMPARE(maxDifference(gb1, br0), 0.0);
    // Different shots: the images differ.
    QVERIFY(maxDifference(ga0, gb0) > 0.1);
    // The second group's passes carry its tag.
    bool tagged = false;
    for (const render::PassStats& p : stats[1].passes) tagged = tagged || p.name == "opaque[g1/left]";
    QVERIFY(tagged);
  }

  void combineIsTheWeightedSum() {
    scene::SceneState s = demo_;
    s.settings.tonemap = scene::Tonemap::None;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.post.lutEnabled = false;  // the demo's LUT is test_post_lut's; here the sum alone
    render::ViewGroup ga{{target(0, a_)}, nullptr};
    render::ViewGroup gb{{target(1, b_)}, nullptr};
    render::GroupCombine combine;
    const render::ViewTarget out = target(3, a_);
    combine.targets = {out};
    combine.weights = {0.25f, 0.75f};
    render::RenderOptions o;
    r_.renderer().renderGroups(s, {ga, gb}, o, &combine);
    const Image combined = r_.renderer().readDisplay(out.fbo, a_.width, a_.height);
    const Image ha = r_.renderer().readHdr(0), hb = r_.renderer().readHdr(1);
    QVERIFY(!ha.rgbaF.empty() && !hb.rgbaF.empty());
    // The CPU's sum of the groups' HDR, sRGB-encoded like the tone map
    // pass without a curve (rows: HDR images are top-down like displays).
    auto srgb = [](double c) {
      c = std::clamp(c, 0.0, 1.0);
      return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    };
    int worst = 0;
    for (size_t p = 0; p < size_t(a_.width) * size_t(a_.height); ++p)
      for (int c = 0; c < 3; ++c) {
        const double v = 0.25 * double(ha.rgbaF[p * 4 + c]) + 0.75 * double(hb.rgbaF[p * 4 + c]);
        worst = std::max(worst, std::abs(int(std::lround(srgb(v) * 255.0)) - int(combined.rgba8[p * 4 + c])));
      }
    qInfo("combined vs the CPU's weighted sum: %d / 255", worst);
    QVERIFY2(worst <= 2, qPrintable(QString::number(worst)));
  }
};

QTEST_GUILESS_MAIN(TestViewGroups)
#include "test_view_groups.moc"
