// Automatic exposure (render/auto_exposure.h, docs/rendering.md "Automatic
// exposure"): a probe meters what the full frame holds (against the test's
// own metering of a full-resolution HDR render: sorted pixels, the
// percentile band's mean), a sun dropping a hundredfold is followed as the
// equation's exact solution says, a frame alone gets the same exposure and
// the same pixels as in a sequence (and a sequence renders one probe per
// grid step), a transition mixes its two shots' exposures, and off renders
// no probe.
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "render/auto_exposure.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "render/stereo_frame_source.h"
#include "scene/animation.h"
#include "scene/light_units.h"
#include "sequencer/frame_range.h"
#include "look_from.h"
#include "post_scene.h"

using namespace hs;

namespace {

constexpr scene::EntityId kSun = 100, kCamera = 200, kSkyCamera = 201;
constexpr double kDrop = 1.0;  // seconds: the sun falls to 1 % (a grid step at 4 probes a second)

// The post tests' scene under a plain sky with two cameras (one down on
// the balls, one up at the sky) and the sun keyed from its full light to 1 % at kDrop.
scene::SceneState sunDropScene() {
  scene::SceneState s = test::postTestScene();
  s.settings.skyZenith = {0.16f, 0.32f, 0.62f};  // a plain sky: the sunlit ground weighs in the metering
  s.settings.skyHorizon = {0.62f, 0.72f, 0.82f};
  test::addPostTestCamera(s, kCamera, "Camera", {0.0, -9.0, 4.0}, {0.0, 0.0, 0.0});
  test::addPostTestCamera(s, kSkyCamera, "Sky camera", {0.0, -9.0, 2.5}, {0.0, 0.0, 9.0});
  const double lux = double(s.entities.at(kSun).light->intensity);
  sequencer::ScalarTrack intensity;
  intensity.property = "light.intensity";
  for (auto [t, v] : {std::pair{0.0, lux}, std::pair{kDrop, lux}, std::pair{kDrop, lux * 0.01}}) {
    sequencer::ScalarKey k;
    k.time = t;
    k.value = v;
    k.interpolation = sequencer::Interpolation::Linear;
    intensity.keys.push_back(k);
  }
  s.sequence.bindings = {sequencer::Binding{kSun, "Sun", {intensity}, std::nullopt}};
  s.settings.post.autoExposure = true;
  return s;
}

// The test's own metering: every pixel's EV100 (Rec. 709 luminance in cd/m²,
// log2(L · 8)), sorted, the mean of the 10..90 % band, clamped.
double meterByHand(const Image& hdr, const scene::PostSettings& p) {
  std::vector<double> ev;
  for (size_t i = 0; i < hdr.pixelCount(); ++i) {
    const float* px = &hdr.rgbaF[i * 4];
    const double nits = (0.2126 * double(px[0]) + 0.7152 * double(px[1]) + 0.0722 * double(px[2])) / scene::sceneUnitsPerNit();
    ev.push_back(std::log2(std::max(nits, 1e-30) * 8.0));
  }
  std::sort(ev.begin(), ev.end());
  const size_t from = size_t(double(ev.size()) * double(p.autoExposureLowPercent) / 100.0);
  const size_t to = size_t(double(ev.size()) * double(p.autoExposureHighPercent) / 100.0);
  double sum = 0.0;
  for (size_t i = from; i < to; ++i) sum += ev[i];
  return std::clamp(sum / double(to - from), double(p.autoExposureMinEv100), double(p.autoExposureMaxEv100));
}

}  // namespace

class TestAutoExposure : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  scene::SceneState doc_ = sunDropScene();
  sequencer::CompiledSequence compiled_ = scene::compileSequence(doc_);

  scene::SceneState at(double t) { return scene::animatedState(doc_, compiled_, t); }
  render::StateAtTime stateAt() {
    return [this](double t) { return at(t); };
  }
  double ev(render::AutoExposure& ae, double t, scene::EntityId cam = kCamera,
            const std::optional<sequencer::Shot>& shot = std::nullopt) {
    return ae.frameEv100(r_.renderer(), stateAt(), at(t), cam, shot, doc_.sequence.rate, t, 16.0 / 9.0);
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void probeMetersWhatTheFrameHolds() {
    const scene::SceneState s = at(0.0);
    const render::RenderView view = render::viewFromCamera(s, kCamera, 384, 216);
    render::AutoExposure ae;
    const double probe = ae.viewEv100(r_.renderer(), s, view);
    const double byHand = meterByHand(r_.render(render::probeState(s), view, true), s.settings.post);
    qInfo("metered EV100 %.3f from a %d-row probe, %.3f by hand at 216 rows", probe, render::AutoExposure::kProbeRows,
          byHand);
    QVERIFY(std::abs(probe - byHand) < 0.3);
    QCOMPARE(ae.probesRendered(), size_t(1));
    QCOMPARE(ae.viewEv100(r_.renderer(), s, view), probe);  // a probe again: the same
    QCOMPARE(ae.probesRendered(), size_t(2));
    // Metering a frame as drawn (the editor's free view): its HDR is before
    // the exposure, so frames drawn at two exposures meter alike, as the
    // probe does.
    for (float drawnAt : {11.0f, 16.5f}) {
      scene::SceneState drawn = render::probeState(s);
      drawn.settings.exposureEv100 = drawnAt;
      const double metered = render::meteredEv100Of(r_.render(drawn, view, true), s.settings.post);
      QVERIFY2(std::abs(metered - byHand) < 0.12, qPrintable(QString("drawn at %1: %2").arg(drawnAt).arg(metered)));
    }
    // Compensation shifts the result by itself.
    scene::SceneState brighter = s;
    brighter.settings.post.autoExposureCompensation = 2.0f;
    QCOMPARE(ae.viewEv100(r_.renderer(), brighter, view), probe - 2.0);  // 2.0f is exact
    QCOMPARE(ae.probesRendered(), size_t(3));
    ae.release();
  }

  void followsTheSunsDropAsTheEquationSays() {
    render::AutoExposure ae;
    const double bright = ev(ae, 0.0);  // the window is one probe: the target itself
    const double dark = ev(ae, 20.0);   // long after: every probe of the window dark
    qInfo("bright target EV100 %.3f, dark %.3f", bright, dark);
    QVERIFY(bright - dark > 1.0);
    QCOMPARE(ev(ae, 0.9), bright);
    // E(t) = dark + (bright − dark)·e^(−speed_down·(t − drop)).
    const double down = double(doc_.settings.post.autoExposureSpeedDown);
    for (double t : {1.0, 1.2, 1.6, 2.5, 4.0}) {
      const double exact = dark + (bright - dark) * std::exp(-down * (t - kDrop));
      QVERIFY2(std::abs(ev(ae, t) - exact) < 1e-6, qPrintable(QString("t %1: %2 vs %3").arg(t).arg(ev(ae, t)).arg(exact)));
    }
    ae.release();
  }

  void aFrameAloneEqualsTheSameFrameInASequence() {
    // Ten seconds at 60 fps: one probe per grid step (4 a second), each once.
    render::AutoExposure sequence;
    double last = 0.0;
    const int64_t frames = 600;
    for (int64_t f = 0; f <= frames; ++f) last = ev(sequence, sequencer::frameTime(f, doc_.sequence.rate));
    QCOMPARE(sequence.probesRendered(), size_t(41));
    render::AutoExposure alone;
    const double single = ev(alone, sequencer::frameTime(frames, doc_.sequence.rate));
    QVERIFY(single == last);  // bit for bit
    QVERIFY(alone.probesRendered() < sequence.probesRendered());
    qInfo("a sequence of %lld frames: %zu probes; its last frame alone: %zu", (long long)frames,
          sequence.probesRendered(), alone.probesRendered());
    sequence.release();
    alone.release();

    // The export's frames (StereoFrameSource): frame 75 alone and after 60..74.
    render::StereoFrameOptions o;
    o.camera = kCamera;
    o.framesInFlight = 1;
    auto render = [&](render::StereoFrameSource& source, int64_t f) {
      sequencer::FrameJob job;
      job.frame = f;
      job.time = sequencer::frameTime(f, doc_.sequence.rate);
      job.eyeWidth = 160;
      job.eyeHeight = 90;
      job.bothEyes = false;
      sequencer::EyeImages out;
      std::string error;
      if (!source.begin(job, error) || !source.finish(job, out, error)) qWarning("frame source: %s", error.c_str());
      return out.left;
    };
    Image inRun;
    {
      render::StereoFrameSource run(r_, doc_, o);
      for (int64_t f = 60; f <= 75; ++f) inRun = render(run, f);
    }
    render::StereoFrameSource single75(r_, doc_, o);
    const Image alone75 = render(single75, 75);
    QVERIFY(!alone75.empty());
    QVERIFY(alone75 == inRun);
    // And it is not the manual exposure's frame.
    scene::SceneState manual = doc_;
    manual.settings.post.autoExposure = false;
    render::StereoFrameSource manualSource(r_, manual, o);
    QVERIFY(render(manualSource, 75) != alone75);
  }

  void aTransitionMixesItsShotsExposures() {
    // Camera into the sky camera at frame 60 (1 s); at 1.5 s, 40 % through.
    render::AutoExposure ae;
    sequencer::Shot outgoing{kCamera, 0, sequencer::Transition::Cut, 0.0, 0, 0};
    sequencer::Shot incoming{kSkyCamera, 0, sequencer::Transition::Cut, 0.0, 60, 0};
    sequencer::Shot both{kCamera, kSkyCamera, sequencer::Transition::Crossfade, 0.4, 0, 60};
    const double a = ev(ae, 1.5, kCamera, outgoing), b = ev(ae, 1.5, kSkyCamera, incoming);
    QVERIFY(std::abs(a - b) > 0.5);  // the sky camera sees another scene
    QVERIFY(std::abs(ev(ae, 1.5, kCamera, both) - (a + 0.4 * (b - a))) < 1e-9);
    // The incoming shot's history begins at its cut: at its first frame it
    // is its own target, whatever came before.
    const double atCut = ev(ae, 1.0, kSkyCamera, incoming);
    render::AutoExposure fresh;
    QCOMPARE(atCut, fresh.viewEv100(r_.renderer(), at(1.0), render::viewFromCamera(at(1.0), kSkyCamera, 128, 72)));
    ae.release();
    fresh.release();
  }

  void offRendersNoProbe() {
    scene::SceneState manual = at(2.0);
    manual.settings.post.autoExposure = false;
    manual.settings.exposureEv100 = 11.25f;
    render::AutoExposure ae;
    QCOMPARE(ae.frameEv100(r_.renderer(), stateAt(), manual, kCamera, std::nullopt, doc_.sequence.rate, 2.0, 1.0),
             11.25);
    QCOMPARE(ae.viewEv100(r_.renderer(), manual, render::viewFromCamera(manual, kCamera, 64, 36)), 11.25);
    QCOMPARE(ae.probesRendered(), size_t(0));
  }
};

QTEST_GUILESS_MAIN(TestAutoExposure)
#include "test_auto_exposure.moc"
