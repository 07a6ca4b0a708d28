// The editor's stereo preview follows the camera cuts
// (app/stereo_preview.h activeCamera): with nothing selected it looks
// through the cut's camera at the shown frame, the stronger shot during a
// transition, the shot camera outside every cut or where a cut's camera is
// gone; a selected camera still wins. During a transition (strictly between
// its first and last frames) it reports the transition to combine
// (activeTransition; the combined picture is test_transitions'). The shot
// (activeShot) says where each camera's cut began.
#include <QtTest>

#include "app/selection.h"
#include "app/stereo_preview.h"
#include "editor_fixture.h"
#include "render/stereo_views.h"

using namespace hs;

class StereoPreviewCutsTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() { app::initApplicationSettings(); }

  void followsTheCutAtTheFrame() {
    scene::SceneState s;
    for (scene::EntityId id : {1, 2, 3}) {
      scene::Entity cam;
      cam.id = id;
      cam.name = "Camera " + std::to_string(id);
      cam.camera = scene::Camera{};
      s.entities[id] = cam;
      s.roots.push_back(id);
    }
    using sequencer::CameraCut, sequencer::Transition;
    s.sequence.cuts = {CameraCut{2, 10, 49}, CameraCut{3, 50, 99, Transition::Crossfade, 10, sequencer::Ease::None}};
    app::StereoPreviewSettings preview;
    app::Selection selection;
    auto at = [&](int64_t frame) {
      s.time.frame = frame;
      return preview.activeCamera(s, selection);
    };
    const scene::EntityId shot = at(0);  // outside every cut: the shot camera
    QCOMPARE(shot, render::shotCamera(s));
    QCOMPARE(at(10), scene::EntityId(2));
    QCOMPARE(at(50), scene::EntityId(2));  // the crossfade's first frame: the shot before
    QCOMPARE(at(54), scene::EntityId(2));  // weights 0.6 / 0.4
    QCOMPARE(at(56), scene::EntityId(3));  // 0.4 / 0.6: the incoming shot is stronger
    QCOMPARE(at(99), scene::EntityId(3));
    QCOMPARE(at(100), shot);
    // The transition the preview combines: only between its first and last frames.
    auto running = [&](int64_t frame) {
      s.time.frame = frame;
      return preview.activeTransition(s, selection);
    };
    QVERIFY(!running(50) && !running(60) && !running(20));
    const auto mid = running(55);
    QVERIFY(mid && mid->camera == 2 && mid->incoming == 3 && mid->transition == Transition::Crossfade);
    QCOMPARE(mid->progress, 0.5);
    // Each camera's shot begins at its cut (automatic exposure adapts from there).
    QCOMPARE(mid->cameraSince, int64_t(10));
    QCOMPARE(mid->incomingSince, int64_t(50));
    auto shotAt = [&](int64_t frame) {
      s.time.frame = frame;
      return preview.activeShot(s, selection);
    };
    QVERIFY(!shotAt(5));  // outside every cut
    QVERIFY(shotAt(30) && shotAt(30)->camera == 2 && shotAt(30)->cameraSince == 10 && !shotAt(30)->incoming);
    QVERIFY(shotAt(70) && shotAt(70)->camera == 3 && shotAt(70)->cameraSince == 50);
    selection.set({1});  // a selected camera wins
    QCOMPARE(at(60), scene::EntityId(1));
    QVERIFY(!running(55));
    QVERIFY(!shotAt(30));
    selection.clear();
    s.entities.at(3).camera.reset();  // the cut's camera is no camera any more
    QCOMPARE(at(70), shot);
    QVERIFY(!running(55));
  }
};

QTEST_MAIN(StereoPreviewCutsTest)
#include "test_stereo_preview_cuts.moc"
