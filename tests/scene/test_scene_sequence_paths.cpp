// Camera paths as document edits (scene/camera_path_edits.h, over
// sequencer/camera_path_edit.h): a path made, its points inserted, deleted
// and moved (a drag is one undo step, a cancelled drag none), aim, banking
// and timing changed, the path removed; every change undone exactly; bad
// paths refused without a step; the speed along a made path constant within
// 0.5% through scene::animatedState, the function export and the viewport use.
#include <QtTest>

#include <cmath>

#include "scene/animation.h"
#include "scene/camera_path_edits.h"
#include "scene/demo_scene.h"
#include "scene/edit.h"
#include "scene/sequence_edits.h"

using namespace hs;
using namespace hs::scene;

namespace {

glm::dvec3 worldPosition(const SceneState& s, EntityId id) { return glm::dvec3(s.worldMatrix(id)[3]); }

// The largest relative deviation of the speed from its mean, from positions
// sampled through animatedState every `dt` over [t0, t1].
double speedDeviation(const SceneState& state, EntityId id, double t0, double t1, int samples, double* meanOut) {
  const sequencer::CompiledSequence compiled = compileSequence(state);
  std::vector<double> speeds;
  const double dt = (t1 - t0) / samples;
  glm::dvec3 prev = worldPosition(animatedState(state, compiled, t0), id);
  for (int i = 1; i <= samples; ++i) {
    const glm::dvec3 p = worldPosition(animatedState(state, compiled, t0 + dt * i), id);
    speeds.push_back(glm::length(p - prev) / dt);
    prev = p;
  }
  double mean = 0.0;
  for (double v : speeds) mean += v;
  mean /= double(speeds.size());
  double worst = 0.0;
  for (double v : speeds) worst = std::max(worst, std::abs(v - mean) / mean);
  if (meanOut) *meanOut = mean;
  return worst;
}

}  // namespace

class TestSequencePaths : public QObject {
  Q_OBJECT

  Document doc_;
  EntityId cam_ = kNoEntity;

 private slots:
  void init() {
    doc_.reset(buildStarterScene(), {});
    cam_ = doc_.state().findByName("Camera");
    QVERIFY(cam_ != kNoEntity);
  }

  void constantSpeedTimingHelpers() {
    const sequencer::ScalarTrack t = sequencer::constantSpeedProgress(2.0, 12.0);
    QCOMPARE(t.keys.size(), size_t(2));
    QCOMPARE(*sequencer::evaluate(t, 2.0), 0.0);
    QCOMPARE(*sequencer::evaluate(t, 7.0), 0.5);
    QCOMPARE(*sequencer::evaluate(t, 12.0), 1.0);
    QCOMPARE(*sequencer::evaluate(t, 20.0), 1.0);  // holds after
    const sequencer::ScalarTrack eased = sequencer::constantSpeedProgress(0.0, 10.0, sequencer::Ease::InOut);
    QVERIFY(*sequencer::evaluate(eased, 1.0) < 0.1);  // soft start
    QCOMPARE(*sequencer::evaluate(eased, 5.0), 0.5);
    // A point inserted after point 0 lies on the curve between the two.
    sequencer::CameraPath path{{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}};
    const glm::dvec3 mid = sequencer::pointAfter(path, 0);
    QVERIFY(mid.x > 2.0 && mid.x < 8.0 && mid.y < 0.0);  // the natural spline bows outward before the turn
    const glm::dvec3 beyond = sequencer::pointAfter(path, 2);
    QVERIFY(beyond.y > 15.0);  // on along the direction of travel
    QVERIFY(!sequencer::pathProblem(sequencer::makePathFollow(path.points, 0, 1)));
  }

  void makeAPathAndUndoIt() {
    // Location and rotation keys: the path replaces them (undo restores).
    QVERIFY(ops::setKeys(doc_, {{cam_, {"transform.translation", TrackKind::Vector}, glm::dvec3(1, 2, 3)}}, 0.0,
                         std::nullopt, "Key"));
    QVERIFY(ops::setKeys(doc_, {{cam_, {"camera.fov_deg", TrackKind::Scalar}, 30.0}}, 0.0, std::nullopt, "Key"));
    const SceneState before = doc_.state();
    const int steps = doc_.undoStack()->count();
    sequencer::PathFollow f = sequencer::makePathFollow({{0, -12, 4}, {10, 0, 5}, {0, 12, 6}}, 0.0, 10.0);
    QVERIFY(ops::setPath(doc_, cam_, f, "Follow path"));
    QCOMPARE(doc_.undoStack()->count(), steps + 1);
    const sequencer::Binding* b = doc_.state().sequence.findBinding(cam_);
    QVERIFY(b && b->path && *b->path == f);
    QCOMPARE(sequencer::trackProperties(*b), (std::vector<std::string>{"camera.fov_deg", "path.progress"}));
    // The camera is on the path: at the start, and at the end at 10 s.
    const auto compiled = compileSequence(doc_.state());
    QVERIFY(glm::length(worldPosition(animatedState(doc_.state(), compiled, 0.0), cam_) - glm::dvec3(0, -12, 4)) < 1e-9);
    QVERIFY(glm::length(worldPosition(animatedState(doc_.state(), compiled, 10.0), cam_) - glm::dvec3(0, 12, 6)) < 1e-9);
    doc_.undoStack()->undo();
    QVERIFY(doc_.state().sequence == before.sequence);
    doc_.undoStack()->redo();
    QVERIFY(ops::removePath(doc_, cam_));
    QVERIFY(!findPath(doc_.state(), cam_));
    QVERIFY(doc_.state().sequence.findBinding(cam_));  // the fov track keeps the binding
    doc_.undoStack()->undo();
    QVERIFY(findPath(doc_.state(), cam_));
  }

  void pointsInsertDeleteMove() {
    QVERIFY(ops::setPath(doc_, cam_, sequencer::makePathFollow({{0, 0, 2}, {10, 0, 2}}, 0.0, 10.0), "Follow path"));
    const int steps = doc_.undoStack()->count();
    QVERIFY(ops::insertPathPoint(doc_, cam_, 2, {10, 10, 2}));
    QVERIFY(ops::insertPathPoint(doc_, cam_, 1, {5, -1, 2}));
    QCOMPARE(findPath(doc_.state(), cam_)->path.points,
             (std::vector<glm::dvec3>{{0, 0, 2}, {5, -1, 2}, {10, 0, 2}, {10, 10, 2}}));
    QCOMPARE(doc_.undoStack()->count(), steps + 2);
    std::string error;
    QVERIFY(!ops::insertPathPoint(doc_, cam_, 9, {0, 0, 0}, &error));
    QVERIFY(error.find("no point 10") != std::string::npos);
    // A drag: many moves with one merge key, one step.
    for (int i = 1; i <= 5; ++i) QVERIFY(ops::movePathPoint(doc_, cam_, 1, {5, -1.0 - i, 2}, "drag-1"));
    QCOMPARE(doc_.undoStack()->count(), steps + 3);
    QCOMPARE(findPath(doc_.state(), cam_)->path.points[1], glm::dvec3(5, -6, 2));
    // A drag that ends where it began leaves no step.
    QVERIFY(ops::movePathPoint(doc_, cam_, 2, {11, 0, 2}, "drag-2"));
    QVERIFY(ops::movePathPoint(doc_, cam_, 2, {10, 0, 2}, "drag-2"));
    QCOMPARE(doc_.undoStack()->count(), steps + 3);
    QVERIFY(ops::removePathPoint(doc_, cam_, 0));
    QVERIFY(ops::removePathPoint(doc_, cam_, 0));
    QVERIFY(!ops::removePathPoint(doc_, cam_, 0, &error));  // two left
    QVERIFY(error.find("at least two points") != std::string::npos);
    QCOMPARE(doc_.undoStack()->count(), steps + 5);
    for (int i = 0; i < 5; ++i) doc_.undoStack()->undo();
    QCOMPARE(findPath(doc_.state(), cam_)->path.points, (std::vector<glm::dvec3>{{0, 0, 2}, {10, 0, 2}}));
  }

  void aimBankingTimingAndRefusals() {
    QVERIFY(ops::setPath(doc_, cam_, sequencer::makePathFollow({{0, 0, 2}, {10, 0, 2}}, 0.0, 10.0), "Follow path"));
    const EntityId sun = doc_.state().findByName("Sun");
    QVERIFY(ops::editPath(doc_, cam_, "aim", [&](sequencer::PathFollow& f) {
      f.aim = sequencer::PathAim::Entity;
      f.targetEntity = sun;
    }));
    QCOMPARE(findPath(doc_.state(), cam_)->targetEntity, sun);
    const int steps = doc_.undoStack()->count();
    std::string error;
    QVERIFY(!ops::editPath(doc_, cam_, "aim", [&](sequencer::PathFollow& f) { f.targetEntity = cam_; }, {}, &error));
    QVERIFY(error.find("cannot look at itself") != std::string::npos);
    QVERIFY(!ops::editPath(doc_, cam_, "aim", [&](sequencer::PathFollow& f) { f.targetEntity = 999; }, {}, &error));
    QVERIFY(!ops::editPath(doc_, cam_, "bank", [](sequencer::PathFollow& f) { f.maxBankDeg = 120; }, {}, &error));
    QVERIFY(error.find("90 degrees") != std::string::npos);
    QVERIFY(!ops::editPath(doc_, cam_, "pts", [](sequencer::PathFollow& f) { f.path.points = {{1, 1, 1}, {1, 1, 1}}; },
                           {}, &error));
    QVERIFY(error.find("no length") != std::string::npos);
    QVERIFY(!ops::setPath(doc_, cam_, sequencer::makePathFollow({{0, 0, std::nan("")}, {1, 0, 0}}, 0, 1), "x", &error));
    QVERIFY(!ops::setPath(doc_, 999, sequencer::makePathFollow({{0, 0, 0}, {1, 0, 0}}, 0, 1), "x", &error));
    QVERIFY(!ops::setPathTiming(doc_, cam_, 5.0, 5.0, sequencer::Ease::None, &error));
    QCOMPARE(doc_.undoStack()->count(), steps);  // nothing refused left a step
    QVERIFY(ops::setPathTiming(doc_, cam_, 2.0, 4.0));
    QCOMPARE(findPath(doc_.state(), cam_)->progress, sequencer::constantSpeedProgress(2.0, 4.0));
    QVERIFY(ops::editPath(doc_, cam_, "bank", [](sequencer::PathFollow& f) {
      f.bank = true;
      f.maxBankDeg = 20;
    }));
    QVERIFY(findPath(doc_.state(), cam_)->bank);
  }

  void pathFromLocationKeysThroughAParent() {
    // A camera under a moved parent: its keys are in the parent's space,
    // the path's points in world space.
    EntityId parent;
    {
      Edit e(doc_, "parent");
      Entity p;
      p.name = "Rig";
      p.transform.translation = {100, 0, 0};
      parent = e.addEntity(p);
      e.reparent(cam_, parent, -1, false);
      QVERIFY(e.commit());
    }
    const AnimTarget loc{"transform.translation", TrackKind::Vector};
    QVERIFY(ops::setKeys(doc_, {{cam_, loc, glm::dvec3(0, 0, 2)}}, 4.0, std::nullopt, "k"));
    QVERIFY(ops::setKeys(doc_, {{cam_, loc, glm::dvec3(10, 0, 2)}}, 1.0, std::nullopt, "k"));
    const LocationKeyPoints keys = locationKeyPoints(doc_.state(), cam_);
    QCOMPARE(keys.points, (std::vector<glm::dvec3>{{110, 0, 2}, {100, 0, 2}}));
    QCOMPARE(keys.first, 1.0);
    QCOMPARE(keys.last, 4.0);
    QVERIFY(ops::setPath(doc_, cam_, sequencer::makePathFollow(keys.points, keys.first, keys.last), "from keys"));
    const auto compiled = compileSequence(doc_.state());
    const SceneState at = animatedState(doc_.state(), compiled, 2.5);
    QVERIFY(glm::length(worldPosition(at, cam_) - glm::dvec3(105, 0, 2)) < 1e-9);
  }

  void speedAlongAMadePathIsConstant() {
    // Uneven spans (3 m to 60 m) and turns, 20 s, sampled every frame at 60 fps
    // through animatedState: the speed deviates from constant by far less than 0.5%.
    const std::vector<glm::dvec3> points{{0, 0, 2}, {3, 0, 2.5}, {40, 20, 8}, {45, 60, 4}, {0, 70, 3}, {-15, 40, 6}};
    QVERIFY(ops::setPath(doc_, cam_, sequencer::makePathFollow(points, 0.0, 20.0), "Follow path"));
    double mean = 0.0;
    const double deviation = speedDeviation(doc_.state(), cam_, 0.0, 20.0, 1200, &mean);
    const double length = sequencer::PathSampler(points).length();
    qInfo("path %.3f m in 20 s: mean speed %.6f m/s (expected %.6f), largest deviation %.3g", length, mean,
          length / 20.0, deviation);
    QVERIFY(std::abs(mean - length / 20.0) / (length / 20.0) < 1e-4);
    QVERIFY2(deviation < 0.005, qPrintable(QString::number(deviation)));
    // Adding and moving points keeps it constant (progress is a share of the length).
    QVERIFY(ops::insertPathPoint(doc_, cam_, 3, {60, 40, 10}));
    QVERIFY(ops::movePathPoint(doc_, cam_, 0, {-5, -5, 1}));
    QVERIFY(speedDeviation(doc_.state(), cam_, 0.0, 20.0, 1200, nullptr) < 0.005);
  }
};

QTEST_GUILESS_MAIN(TestSequencePaths)
#include "test_scene_sequence_paths.moc"
