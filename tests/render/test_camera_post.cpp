// A camera's own post settings in the renderer (scene/camera_post.h,
// docs/rendering.md "Post settings on cameras"): a view through a camera
// is the picture of a scene whose own settings hold the camera's values
// (byte for byte), a free view keeps the scene's, both eyes of a rig share
// the camera's chain; a transition between shots whose chains differ
// combines their finished pictures (against the CPU twin of the
// combination: a weighted sum, and the swipe's pattern), one whose chains
// are alike combines in linear light before one chain, with no copy of
// the pictures.
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "pass_stats.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "render/stereo_views.h"
#include "scene/camera_post.h"
#include "post_scene.h"
#include "transition_reference.h"

using namespace hs;
using test::passRan;

namespace {

constexpr scene::EntityId kShotA = 200, kShotB = 201;
constexpr int kW = 160, kH = 90;

// The post tests' scene with two cameras; shot B overrides nothing yet.
scene::SceneState twoShots() {
  scene::SceneState s = test::postTestScene();
  test::addPostTestCamera(s, kShotA, "Shot A", {0.0, -9.0, 2.5}, {0.0, 0.0, 1.2});
  test::addPostTestCamera(s, kShotB, "Shot B", {7.0, -6.0, 3.0}, {0.0, 0.0, 1.0});
  return s;
}

void set(scene::SceneState& s, scene::EntityId cam, const char* key, const scene::FieldValue& v) {
  scene::findEntityField(std::string("camera.post.") + key)->set(s.entities.at(cam), v);
}

// Shot B graded apart: no tone map, a strong vignette.
scene::SceneState gradedShotB() {
  scene::SceneState s = twoShots();
  set(s, kShotB, "tonemap", int64_t(scene::Tonemap::None));
  set(s, kShotB, "vignette.enabled", true);
  set(s, kShotB, "vignette.intensity", 0.8);
  return s;
}

render::RenderView through(const scene::SceneState& s, scene::EntityId cam) {
  return render::viewFromCamera(s, cam, kW, kH);
}

// 8-bit display pixels as floats 0..1 (the transition twin's input).
Image asFloat(const Image& img) {
  Image out = Image::makeF(img.width, img.height);
  for (size_t i = 0; i < img.rgba8.size(); ++i) out.rgbaF[i] = float(img.rgba8[i]) / 255.0f;
  return out;
}

double worstDifference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.rgbaF.size() != b.rgbaF.size()) return INFINITY;
  double worst = 0.0;
  for (size_t i = 0; i < a.rgbaF.size(); ++i)
    if (i % 4 != 3) worst = std::max(worst, double(std::abs(a.rgbaF[i] - b.rgbaF[i])));
  return worst;
}


}  // namespace

class TestCameraPostRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void aCameraShowsTheSceneWithItsValues() {
    const scene::SceneState graded = gradedShotB();
    scene::SceneState byScene = twoShots();
    byScene.settings.tonemap = scene::Tonemap::None;
    byScene.settings.post.vignette = true;
    byScene.settings.post.vignetteIntensity = 0.8f;
    const Image mine = r_.render(graded, through(graded, kShotB));
    QVERIFY(!mine.empty());
    QVERIFY(mine == r_.render(byScene, through(byScene, kShotB)));
    // The scene's own picture differs; a free view from the same place
    // (no camera's) keeps the scene's settings, as does the other camera.
    const scene::SceneState plain = twoShots();
    const Image sceneOwn = r_.render(plain, through(plain, kShotB));
    QVERIFY(mine != sceneOwn);
    render::RenderView free = through(graded, kShotB);
    free.camera = scene::kNoEntity;
    QVERIFY(r_.render(graded, free) == sceneOwn);
    QVERIFY(r_.render(graded, through(graded, kShotA)) == r_.render(plain, through(plain, kShotA)));
    // Both eyes of a rig are the camera's views.
    scene::SceneState rig = graded;
    rig.entities.at(kShotB).camera->stereo = scene::Camera::Stereo::OffAxis;
    const render::EyeViews eyes = render::eyeViews(rig, kShotB, kW, kH);
    QVERIFY(eyes.stereo);
    QCOMPARE(eyes.left.camera, kShotB);
    QCOMPARE(eyes.right.camera, kShotB);
  }

  // Shots graded apart: each runs its own chain, the transition combines
  // the finished pictures as the CPU twin does (a weighted sum; the
  // swipe's edge), within a 1/255 rounding.
  void differingChainsCombineTheirPictures() {
    const scene::SceneState s = gradedShotB();
    const render::RenderView a = through(s, kShotA), b = through(s, kShotB);
    const Image pictureA = asFloat(r_.render(s, a)), pictureB = asFloat(r_.render(s, b));
    render::FrameStats stats;
    const Image mixed = asFloat(r_.renderMix(s, {a, b}, {0.65f, 0.35f}, false, &stats));
    Image sum = Image::makeF(kW, kH);
    for (size_t i = 0; i < sum.rgbaF.size(); ++i) sum.rgbaF[i] = 0.65f * pictureA.rgbaF[i] + 0.35f * pictureB.rgbaF[i];
    const double worst = worstDifference(mixed, sum);
    QVERIFY2(worst <= 1.0 / 255.0 + 1e-6, qPrintable(QString("worst %1").arg(worst * 255.0)));
    QVERIFY(passRan(stats, "picture_combine"));
    QVERIFY(passRan(stats, "group0_picture_copy"));
    QVERIFY(passRan(stats, "group1_picture_copy"));

    render::GroupCombine swipe;
    swipe.transition = sequencer::Transition::Swipe;
    swipe.progress = 0.5f;
    const Image swiped = asFloat(r_.renderMix(s, {a, b}, {0.5f, 0.5f}, false, nullptr, {}, &swipe));
    const Image twin = test::transitionReference(pictureA, pictureB, sequencer::Transition::Swipe, 0.5, 0);
    const double worstSwipe = worstDifference(swiped, twin);
    QVERIFY2(worstSwipe <= 1.0 / 255.0 + 1e-6, qPrintable(QString("worst %1").arg(worstSwipe * 255.0)));
  }

  // Cameras whose chains are alike (none overrides, or both the same way):
  // linear light mixed before one chain, the camera's, and no copy of the
  // pictures (nothing the scene does not need).
  void alikeChainsCombineInLinearLight() {
    scene::SceneState both = twoShots();
    for (scene::EntityId c : {kShotA, kShotB}) set(both, c, "tonemap", int64_t(scene::Tonemap::AgX));
    scene::SceneState byScene = twoShots();
    byScene.settings.tonemap = scene::Tonemap::AgX;
    render::FrameStats stats;
    const Image mixed = r_.renderMix(both, {through(both, kShotA), through(both, kShotB)}, {0.4f, 0.6f}, false, &stats);
    QVERIFY(mixed == r_.renderMix(byScene, {through(byScene, kShotA), through(byScene, kShotB)}, {0.4f, 0.6f}));
    QVERIFY(passRan(stats, "group_combine"));
    QVERIFY(!passRan(stats, "group0_picture_copy"));
    QVERIFY(!passRan(stats, "picture_combine"));
    // The linear mix differs from a mix of the pictures (what tells the two apart).
    const Image pictures = r_.renderMix(gradedShotB(), {through(both, kShotA), through(both, kShotB)}, {0.4f, 0.6f});
    QVERIFY(pictures != mixed);
  }
};

QTEST_GUILESS_MAIN(TestCameraPostRender)
#include "test_camera_post.moc"
