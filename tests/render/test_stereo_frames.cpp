// Stereo frames from the real renderer (headless EGL, llvmpipe): the export's
// frame source against plain renders, determinism across runs, contexts and
// frame order, off-axis frusta meeting at the convergence distance, identical
// eyes at interaxial 0, mono cameras, depth readback for the comfort check,
// and the 16-bit and float pixel paths.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "file_bytes.h"
#include "core/srgb.h"
#include "mesh/mesh_data.h"
#include "render/export_job_tag.h"
#include "render/offscreen_renderer.h"
#include "render/stereo_frame_source.h"
#include "render/stereo_views.h"
#include "scene/animation.h"
#include "scene/demo_scene.h"
#include "scene/transform.h"
#include "sequencer/export_loop.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 96, kH = 54;

scene::SceneState demo() {
  std::string error;
  auto s = scene::buildDemoScene(error);
  if (!s) qFatal("demo: %s", error.c_str());
  return *s;
}

// Renders `frames` of `scene` through the frame source into `dir` as PNGs.
sequencer::ExportResult exportFrames(render::OffscreenRenderer& r, const scene::SceneState& scene,
                                     const std::string& frames, const std::string& dir, int inFlight = 2,
                                     sequencer::StereoLayout layout = sequencer::StereoLayout::SideBySide) {
  sequencer::ExportSettings s;
  std::string error;
  s.frames = *sequencer::FrameList::parse(frames, error);
  s.output = dir + "/f_%03d.png";
  s.eyeWidth = kW;
  s.eyeHeight = kH;
  s.layout = layout;
  s.rate = scene.sequence.rate;
  render::StereoFrameOptions o;
  o.framesInFlight = inFlight;
  render::StereoFrameSource source(r, scene, o);
  return sequencer::runExport(s, source);
}

std::string frameFile(const std::string& dir, int f) {
  char name[32];
  std::snprintf(name, sizeof name, "/f_%03d.png", f);
  return dir + name;
}

// One view of frame `frame` through the source (sbs, both eyes kept apart).
sequencer::EyeImages sourceFrame(render::OffscreenRenderer& r, const scene::SceneState& s,
                                 const render::StereoFrameOptions& o, int64_t frame, int w = kW, int h = kH,
                                 bool bothEyes = true, bool floatPixels = false) {
  render::StereoFrameSource source(r, s, o);
  sequencer::FrameJob job;
  job.frame = frame;
  job.time = sequencer::frameTime(frame, s.sequence.rate);
  job.eyeWidth = w;
  job.eyeHeight = h;
  job.bothEyes = bothEyes;
  job.floatPixels = floatPixels;
  sequencer::EyeImages out;
  std::string error;
  if (!source.begin(job, error) || !source.finish(job, out, error)) qWarning("frame source: %s", error.c_str());
  return out;
}

scene::EntityId addEntity(scene::SceneState& s, scene::Entity e) {
  e.id = s.maxEntityId() + 1;
  s.roots.push_back(e.id);
  const scene::EntityId id = e.id;
  s.entities.emplace(id, std::move(e));
  return id;
}

// A black vertical strip, `width` x 2 m, facing -Y (the camera), centred on its origin.
std::shared_ptr<const mesh::MeshData> strip(float width) {
  auto m = std::make_shared<mesh::MeshData>();
  const float w = width * 0.5f;
  m->positions = {{-w, 0, 1}, {w, 0, 1}, {w, 0, -1}, {-w, 0, -1}};
  m->normals.assign(4, glm::vec3(0, -1, 0));
  m->indices = {0, 2, 1, 0, 3, 2};
  mesh::Material mat;
  mat.baseColor = glm::vec4(0, 0, 0, 1);
  m->materials.push_back(mat);
  m->submeshes.push_back({0, 6, 0});
  return m;
}

// A white world (sky and ambient), a camera at the origin looking along +Y
// with an off-axis rig converging at `convergence`, and black strips at the
// given distances, each at x = 0 (the rig's midline).
scene::SceneState stripScene(double convergence, double interaxial, const std::vector<double>& distances) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::Msaa4;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = glm::vec3(1.0f);
  auto mesh = strip(0.02f);
  scene::MeshAsset a;
  a.id = 1;
  a.name = "strip";
  a.contentHash = mesh::contentHash(*mesh);
  a.data = mesh;
  s.assets.emplace(a.id, a);
  for (double d : distances) {
    scene::Entity e;
    e.name = "strip " + std::to_string(d);
    e.mesh = scene::MeshInstance{1};
    e.transform.translation = {0.0, d, 1.0};
    addEntity(s, e);
  }
  scene::Entity cam;
  cam.name = "Rig";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 30.0;
  cam.camera->stereo = scene::Camera::Stereo::OffAxis;
  cam.camera->interaxial = interaxial;
  cam.camera->convergence = convergence;
  cam.transform.translation = {0.0, 0.0, 1.0};
  cam.transform.rotation = scene::fromEulerDegrees({90.0, 0.0, 0.0});  // -Z forward turned to +Y
  addEntity(s, cam);
  return s;
}

// Horizontal centre of the dark pixels of row y (darkness-weighted), or NaN.
double darkCentre(const hs::Image& img, int y) {
  double sum = 0.0, weighted = 0.0;
  for (int x = 0; x < img.width; ++x) {
    const uint8_t* p = &img.rgba8[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
    const double dark = 1.0 - double(p[0]) / 255.0;
    if (dark < 0.02) continue;
    sum += dark;
    weighted += dark * (x + 0.5);
  }
  return sum > 0.0 ? weighted / sum : std::nan("");
}

// The strip's screen disparity (right eye minus left) in pixels, averaged
// over rows in the middle of the image.
double disparity(const sequencer::EyeImages& eyes) {
  double total = 0.0;
  int rows = 0;
  for (int y = eyes.left.height / 3; y < eyes.left.height * 2 / 3; ++y) {
    const double l = darkCentre(eyes.left, y), r = darkCentre(eyes.right, y);
    if (std::isnan(l) || std::isnan(r)) continue;
    total += r - l;
    ++rows;
  }
  return rows ? total / rows : std::nan("");
}

}  // namespace

class TestStereoFrames : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  QTemporaryDir tmp_;

  std::string dir(const char* name) {
    const std::string d = tmp_.path().toStdString() + "/" + name;
    fs::create_directories(d);
    return d;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    QVERIFY(tmp_.isValid());
  }

  void sourceMatchesAPlainRenderOfTheAnimatedScene() {
    // What the pixel-buffer path hands over is exactly what a synchronous
    // render and readback of the animated scene gives (row order, eyes).
    const scene::SceneState s = demo();
    const scene::EntityId cam = render::shotCamera(s);
    QCOMPARE(s.find(cam)->name, std::string("Flight Camera"));
    const int64_t frame = 200;
    const sequencer::EyeImages eyes = sourceFrame(r_, s, {}, frame);
    const scene::SceneState at =
        scene::animatedState(s, scene::compileSequence(s), sequencer::frameTime(frame, s.sequence.rate));
    const render::EyeViews v = render::eyeViews(at, cam, kW, kH);
    QVERIFY(v.stereo);
    QVERIFY(v.left.projectionShift.x < 0.0 && v.right.projectionShift.x > 0.0);
    // As the export draws each eye: levels of detail and the frame origin
    // from the mono camera (renderer.h).
    render::RenderOptions o;
    o.lodView = &v.mono;
    const hs::Image l = r_.render(at, v.left, false, nullptr, o), r = r_.render(at, v.right, false, nullptr, o);
    QVERIFY(eyes.left.rgba8 == l.rgba8);
    QVERIFY(eyes.right.rgba8 == r.rgba8);
    QVERIFY(eyes.left.rgba8 != eyes.right.rgba8);  // a stereo pair, not one view twice
  }

  void framesAreTheSameInAnyRunAnyContextAnyOrder() {
    const scene::SceneState s = demo();
    // One run of frames 0-11, two frames in flight.
    const std::string whole = dir("whole");
    auto r = exportFrames(r_, s, "0-11", whole);
    QVERIFY2(r.ok, r.error.c_str());
    QCOMPARE(r.written, int64_t(12));
    // Two separate runs (each with a fresh GL context), the later half
    // first, one of them reading back each frame before the next.
    const std::string split = dir("split");
    {
      render::OffscreenRenderer other;
      std::string error;
      QVERIFY2(other.initialize(error), error.c_str());
      r = exportFrames(other, s, "6-11", split, 1);
      QVERIFY2(r.ok, r.error.c_str());
    }
    {
      render::OffscreenRenderer other;
      std::string error;
      QVERIFY2(other.initialize(error), error.c_str());
      r = exportFrames(other, s, "3,0-2,4-5", split);
      QVERIFY2(r.ok, r.error.c_str());
    }
    for (int f = 0; f <= 11; ++f) {
      const std::string a = test::readFile(frameFile(whole, f)), b = test::readFile(frameFile(split, f));
      QVERIFY2(!a.empty() && a == b, qPrintable(QString("frame %1 differs between runs").arg(f)));
    }
    // Consecutive frames differ: the camera flies.
    QVERIFY(test::readFile(frameFile(whole, 0)) != test::readFile(frameFile(whole, 11)));
    // And a frame rendered alone, after many others in this context, is the same file.
    const std::string alone = dir("alone");
    r = exportFrames(r_, s, "9", alone);
    QVERIFY2(r.ok, r.error.c_str());
    QVERIFY(test::readFile(frameFile(alone, 9)) == test::readFile(frameFile(whole, 9)));
  }

  void offAxisFrustaMeetAtTheConvergenceDistance() {
    // A thin strip exactly at the convergence distance has zero disparity
    // between the eyes; one nearer has the negative (crossed) disparity the
    // rig maths predicts, P(Z) = b / (2 tan(fovX/2)) (1/C - 1/Z) of the width.
    const double C = 6.0, b = 0.3;
    const int w = 320, h = 180;
    const sequencer::EyeImages at = sourceFrame(r_, stripScene(C, b, {C}), {}, 0, w, h);
    const double dAt = disparity(at);
    qInfo("strip at the convergence distance (%.1f m): disparity %.4f px", C, dAt);
    QVERIFY(std::abs(dAt) < 0.02);
    const double Z = 3.0;
    const sequencer::EyeImages near = sourceFrame(r_, stripScene(C, b, {Z}), {}, 0, w, h);
    const double dNear = disparity(near);
    const double tanHalfX = std::tan(glm::radians(30.0) / 2.0) * double(w) / double(h);
    const double expected = b / (2.0 * tanHalfX) * (1.0 / C - 1.0 / Z) * w;
    qInfo("strip at %.1f m: disparity %.3f px (predicted %.3f px)", Z, dNear, expected);
    QVERIFY(dNear < -1.0);
    QVERIFY(std::abs(dNear - expected) < 0.1);
    // And behind the convergence plane, positive (uncrossed).
    QVERIFY(disparity(sourceFrame(r_, stripScene(C, b, {12.0}), {}, 0, w, h)) > 1.0);
  }

  void interaxialZeroGivesIdenticalEyes() {
    for (auto mode : {scene::Camera::Stereo::OffAxis, scene::Camera::Stereo::Parallel, scene::Camera::Stereo::ToeIn}) {
      scene::SceneState s = demo();
      const scene::EntityId cam = render::shotCamera(s);
      s.entities[cam].camera->stereo = mode;
      s.entities[cam].camera->interaxial = 0.0;
      s.sequence.findBinding(cam)->tracks.clear();  // the demo animates the interaxial
      const sequencer::EyeImages eyes = sourceFrame(r_, s, {}, 120);
      QVERIFY(!eyes.left.rgba8.empty());
      QVERIFY2(eyes.left.rgba8 == eyes.right.rgba8, "eyes differ at interaxial 0");
    }
  }

  void monoCameraRendersOneViewForBothEyes() {
    scene::SceneState s = demo();
    render::StereoFrameOptions o;
    o.camera = s.findByName("Main Camera");
    const sequencer::EyeImages both = sourceFrame(r_, s, o, 0);
    QVERIFY(both.left.rgba8 == both.right.rgba8);
    const scene::SceneState at = scene::animatedState(s, scene::compileSequence(s), 0.0);
    const hs::Image plain = r_.render(at, render::viewFromCamera(at, o.camera, kW, kH));
    QVERIFY(both.left.rgba8 == plain.rgba8);
    // The mono layout of a stereo camera renders the rig's centre view only.
    const sequencer::EyeImages mono = sourceFrame(r_, s, {}, 0, kW, kH, false);
    QVERIFY(mono.right.empty());
    QVERIFY(mono.left.rgba8 == r_.render(at, render::viewFromCamera(at, render::shotCamera(s), kW, kH)).rgba8);
  }

  void depthGivesTheComfortCheckTheStripsParallax() {
    const double C = 6.0, b = 0.3;
    render::StereoFrameOptions o;
    o.comfort = sequencer::ComfortOptions{};
    o.comfort->skyAtInfinity = false;
    render::StereoFrameSource source(r_, stripScene(C, b, {3.0, 10.0}), o);
    sequencer::FrameJob job;
    job.eyeWidth = 320;
    job.eyeHeight = 180;
    sequencer::EyeImages out;
    std::string error;
    QVERIFY2(source.begin(job, error) && source.finish(job, out, error), error.c_str());
    QCOMPARE(source.comfort().size(), size_t(1));
    const sequencer::ComfortResult& c = source.comfort()[0].result;
    QVERIFY(c.hasPixels);
    const double tanHalfX = std::tan(glm::radians(30.0) / 2.0) * 320.0 / 180.0;
    auto parallax = [&](double z) { return b / (2.0 * tanHalfX) * (1.0 / C - 1.0 / z); };
    qInfo("nearest %.4f%% at %.3f m, farthest %.4f%% at %.3f m", c.nearestParallax * 100, c.nearestDepth,
          c.farthestParallax * 100, c.farthestDepth);
    QVERIFY(std::abs(c.nearestDepth - 3.0) < 1e-3);
    QVERIFY(std::abs(c.farthestDepth - 10.0) < 1e-3);
    QVERIFY(std::abs(c.nearestParallax - parallax(3.0)) < 1e-5);
    QVERIFY(std::abs(c.farthestParallax - parallax(10.0)) < 1e-5);
    QVERIFY(!c.withinBudget);  // -5.2% is far in front of the default -1% limit
  }

  void sixteenBitAndFloatPixels() {
    const scene::SceneState s = demo();
    render::StereoFrameOptions o;
    o.displayBits16 = true;
    const sequencer::EyeImages deep = sourceFrame(r_, s, o, 30);
    QVERIFY(deep.left.isFloat() && deep.right.isFloat());
    const sequencer::EyeImages eight = sourceFrame(r_, s, {}, 30);
    // The 16-bit display value is the 8-bit one with more precision.
    int worst = 0;
    for (size_t i = 0; i < eight.left.rgba8.size(); ++i) {
      if (i % 4 == 3) continue;
      const int v16 = int(std::lround(hs::linearToSrgbFloat(deep.left.rgbaF[i]) * 255.0f));
      worst = std::max(worst, std::abs(v16 - int(eight.left.rgba8[i])));
    }
    QVERIFY2(worst <= 1, qPrintable(QString("16-bit and 8-bit differ by %1").arg(worst)));
    const sequencer::EyeImages hdr = sourceFrame(r_, s, {}, 30, kW, kH, true, true);
    QVERIFY(hdr.left.isFloat());
    QVERIFY(*std::max_element(hdr.left.rgbaF.begin(), hdr.left.rgbaF.end()) > 0.0f);
  }

  void jobTagFollowsSceneAndSettings() {
    const scene::SceneState s = demo();
    sequencer::ExportSettings e;
    const std::string tag = render::exportJobTag(s, 7, e, {});
    QCOMPARE(render::exportJobTag(demo(), 7, e, {}), tag);  // the same scene built again
    scene::SceneState moved = s;
    moved.entities.begin()->second.transform.translation.x += 0.001;
    QVERIFY(render::exportJobTag(moved, 7, e, {}) != tag);
    e.eyeWidth = 1280;
    QVERIFY(render::exportJobTag(s, 7, e, {}) != tag);
  }
};

QTEST_GUILESS_MAIN(TestStereoFrames)
#include "test_stereo_frames.moc"
