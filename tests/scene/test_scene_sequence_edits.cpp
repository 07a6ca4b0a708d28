// Key edits: which track a field's key goes into, keys set/replaced/removed
// as undoable edits (one step each, exact undo), retiming (drags computed
// from the start, snapped to frames, overlaps replaced), copy and paste,
// frame rate and range.
#include <QtTest>

#include "scene/demo_scene.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/sequence_edits.h"
#include "scene/animation.h"
#include "scene/transform.h"

using namespace hs;
using namespace hs::scene;
using sequencer::KeyRef;

namespace {

Document& demoDoc() {
  static Document doc;
  std::string error;
  auto s = buildDemoScene(error);
  if (!s) qFatal("%s", error.c_str());
  doc.reset(*s, {});
  return doc;
}

AnimTarget target(const char* path) {
  std::string error;
  auto t = animationTarget(path, error);
  if (!t) qFatal("%s", error.c_str());
  return *t;
}

}  // namespace

class TestSequenceEdits : public QObject {
  Q_OBJECT

 private slots:
  void fieldsMapToTracks() {
    std::string error;
    QCOMPARE(animationTarget("transform.rotation_deg", error)->property, std::string("transform.rotation"));
    QCOMPARE(animationTarget("transform.rotation_deg", error)->kind, TrackKind::Rotation);
    QCOMPARE(animationTarget("transform.translation", error)->kind, TrackKind::Vector);
    QCOMPARE(animationTarget("camera.interaxial_m", error)->kind, TrackKind::Scalar);
    QCOMPARE(animationTarget("entity.visible", error)->kind, TrackKind::Step);
    QCOMPARE(animationTarget("mesh.tint", error)->kind, TrackKind::Vector);
    QVERIFY(!animationTarget("entity.name", error));
    QVERIFY(error.find("cannot be animated") != std::string::npos);
    QVERIFY(!animationTarget("camera.stereo", error));  // an enum
    QVERIFY(!animationTarget("camera.zoom", error));
    const auto q = parseKeyValue(target("transform.rotation_deg"), "0,0,90", error);
    QVERIFY(q && std::holds_alternative<glm::dquat>(*q));
    QVERIFY(glm::length(eulerDegrees(std::get<glm::dquat>(*q)) - glm::dvec3(0, 0, 90)) < 1e-9);
    QVERIFY(!parseKeyValue(target("camera.fov_deg"), "wide", error));
  }

  void setKeysIsOneUndoStepAndReplacesAtTheSameTime() {
    Document& doc = demoDoc();
    const SceneState before = doc.state();
    const EntityId cam = doc.state().findByName("Main Camera");
    const EntityId bunny = doc.state().findByName("Stanford Bunny");
    const int steps = doc.undoStack()->count();
    QVERIFY(ops::setKeys(doc, {{cam, target("camera.fov_deg"), 35.0}, {bunny, target("transform.translation"), glm::dvec3(1, 2, 3)}},
                         1.0, sequencer::Interpolation::Linear, "Key"));
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    QVERIFY(isAnimated(doc.state().sequence, cam, "camera.fov_deg"));
    QVERIFY(hasKeyAt(doc.state().sequence, cam, "camera.fov_deg", 1.0));
    QVERIFY(ops::setKeys(doc, {{cam, target("camera.fov_deg"), 30.0}}, 0.0, std::nullopt, "Key"));
    QVERIFY(ops::setKeys(doc, {{cam, target("camera.fov_deg"), 40.0}}, 1.0, std::nullopt, "Key"));  // replaces
    const auto& track = std::get<sequencer::ScalarTrack>(doc.state().sequence.findBinding(cam)->tracks[0]);
    QCOMPARE(track.keys.size(), size_t(2));
    QCOMPARE(track.keys[0].time, 0.0);
    QCOMPARE(track.keys[1].value, 40.0);
    QCOMPARE(track.keys[1].interpolation, sequencer::Interpolation::Linear);  // kept from the first key there
    // Wrong kinds and components are refused without an undo step.
    std::string error;
    QVERIFY(!ops::setKeys(doc, {{cam, target("camera.fov_deg"), glm::dvec3(1)}}, 2.0, std::nullopt, "Key", {}, &error));
    QVERIFY(!ops::setKeys(doc, {{bunny, target("camera.fov_deg"), 20.0}}, 2.0, std::nullopt, "Key", {}, &error));
    QVERIFY(error.find("camera") != std::string::npos);
    while (doc.undoStack()->index() > steps) doc.undoStack()->undo();
    QVERIFY(doc.state().sequence == before.sequence);
  }

  void retimeRemoveCopyPaste() {
    Document& doc = demoDoc();
    const EntityId spin = doc.state().findByName("Bunny (instance)");
    const sequencer::Sequence start = doc.state().sequence;
    // A drag of key 1 of the rotation track by +0.4 s, in three moves, each
    // computed from the start: the keys end where the last move says.
    std::vector<KeyRef> moved;
    for (double dt : {0.1, 0.25, 0.4}) {
      sequencer::Sequence s = start;
      moved = sequencer::moveKeys(s, {{spin, "transform.rotation", 1}}, dt);
      QVERIFY(ops::replaceSequence(doc, s, "Move keys", "drag-1"));
    }
    QCOMPARE(moved.size(), size_t(1));
    QCOMPARE(*sequencer::keyTime(doc.state().sequence, moved[0]), 10.0 / 12.0 + 0.4);
    doc.undoStack()->undo();  // the whole drag is one step
    QVERIFY(doc.state().sequence == start);
    // Snapped to frames, and onto another key's time: the moved key replaces it.
    sequencer::Sequence s = start;
    const double dt = 10.0 / 12.0 + 0.004;  // key 1 lands on key 2's time (within a frame)
    moved = sequencer::moveKeysSnapped(s, {{spin, "transform.rotation", 1}}, dt, s.rate);
    QCOMPARE(sequencer::keyTimes(s, spin, "transform.rotation").size(), size_t(12));
    QCOMPARE(*sequencer::keyTime(s, moved[0]), sequencer::frameTime(100, s.rate));
    // Copy two keys, paste at 20 s: relative times kept.
    s = start;
    const sequencer::KeyClipboard clip =
        sequencer::copyKeys(s, {{spin, "transform.rotation", 2}, {spin, "transform.translation", 3}});
    QCOMPARE(clip.entries.size(), size_t(2));
    const std::vector<KeyRef> pasted = sequencer::pasteKeys(s, clip, 20.0);
    QCOMPARE(pasted.size(), size_t(2));
    QCOMPARE(*sequencer::keyTime(s, pasted[0]), 20.0);
    QVERIFY(std::abs(*sequencer::keyTime(s, pasted[1]) - (20.0 + 10.0 / 12.0)) < 1e-12);
    // Remove every key of a binding: the binding goes too; undo brings it back.
    std::vector<KeyRef> all;
    for (const KeyRef& k : sequencer::allKeys(doc.state().sequence))
      if (k.entity == spin) all.push_back(k);
    QCOMPARE(all.size(), size_t(26));
    QVERIFY(ops::removeKeys(doc, all));
    QVERIFY(!doc.state().sequence.findBinding(spin));
    doc.undoStack()->undo();
    QVERIFY(doc.state().sequence == start);
    // The path's progress track is addressed as path.progress.
    const EntityId flight = doc.state().findByName("Flight Camera");
    QCOMPARE(sequencer::keyTimes(doc.state().sequence, flight, sequencer::kPathProgress), (std::vector<double>{0.0, 10.0}));
  }

  void pathCameraUnderAParentStaysOnItsPath() {
    // A path gives world poses; under a moved and turned parent the camera
    // still sits on the path, looking where the path aims.
    std::string error;
    SceneState s = *buildDemoScene(error);
    const EntityId flight = s.findByName("Flight Camera");
    const SceneState plain = animatedState(s, compileSequence(s), 3.0);
    Entity rig;
    rig.id = s.maxEntityId() + 1;
    rig.name = "Rig";
    rig.transform.translation = {5.0, -2.0, 1.0};
    rig.transform.rotation = fromEulerDegrees({0.0, 0.0, 30.0});
    rig.children = {flight};
    s.roots.erase(std::find(s.roots.begin(), s.roots.end(), flight));
    s.roots.push_back(rig.id);
    s.entities[flight].parent = rig.id;
    s.entities.emplace(rig.id, rig);
    QVERIFY(s.validate().empty());
    const SceneState parented = animatedState(s, compileSequence(s), 3.0);
    const glm::dmat4 a = plain.worldMatrix(flight), b = parented.worldMatrix(flight);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) QVERIFY2(std::abs(a[c][r] - b[c][r]) < 1e-9, "the parented camera left its path");
  }

  void rateAndRange() {
    Document& doc = demoDoc();
    QVERIFY(ops::setFrameRate(doc, {30, 1}));
    QVERIFY(ops::setFrameRange(doc, 10, 20));
    QVERIFY(!ops::setFrameRange(doc, 20, 10));
    QCOMPARE(doc.state().sequence.startFrame, int64_t(10));
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    QCOMPARE(doc.state().sequence.rate, (sequencer::FrameRate{60, 1}));
    QCOMPARE(doc.state().sequence.endFrame, int64_t(599));
  }
};

QTEST_GUILESS_MAIN(TestSequenceEdits)
#include "test_scene_sequence_edits.moc"
