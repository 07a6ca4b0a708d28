// The timeline inside the document: sequence edits are undoable like any
// other, follow entities through delete/duplicate, survive the .hscene file,
// and animatedState() writes the sampled values into the scene.
#include <QtTest>

#include <QTemporaryDir>

#include "scene/animation.h"
#include "scene/demo_scene.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::scene;

namespace {

sequencer::ScalarTrack fovTrack() {
  sequencer::ScalarTrack t;
  t.property = "camera.fov_deg";
  sequencer::ScalarKey a, b;
  a.time = 0.0;
  a.value = 50.0;
  b.time = 2.0;
  b.value = 30.0;
  t.keys = {a, b};
  return t;
}

EntityId cameraOf(const Document& doc) { return doc.state().cameras().front(); }

void animateCamera(Document& doc) {
  Edit e(doc, "Animate camera");
  const EntityId cam = cameraOf(doc);
  sequencer::Binding b;
  b.entity = cam;
  b.label = doc.state().find(cam)->name;
  b.tracks.push_back(fovTrack());
  sequencer::VectorTrack move;
  move.property = "transform.translation";
  sequencer::VectorKey k0, k1;
  k0.time = 0.0;
  k0.value = {0, -12, 4};
  k1.time = 2.0;
  k1.value = {10, -12, 4};
  k0.interpolation = sequencer::Interpolation::Linear;
  move.keys = {k0, k1};
  b.tracks.push_back(move);
  sequencer::StepTrack vis;
  vis.property = "entity.visible";
  vis.keys = {{0.0, true}, {1.0, false}};
  b.tracks.push_back(vis);
  e.sequence().bindings.push_back(b);
  e.commit();
}

}  // namespace

class TestSceneSequence : public QObject {
  Q_OBJECT
 private slots:
  void sequenceEditsUndoExactly() {
    Document doc;
    doc.reset(buildStarterScene(), {});
    const std::string before = canonicalJson(doc.state());
    animateCamera(doc);
    const std::string after = canonicalJson(doc.state());
    QVERIFY(before != after);
    QCOMPARE(doc.state().sequence.bindings.size(), size_t(1));
    doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), before);
    doc.undoStack()->redo();
    QCOMPARE(canonicalJson(doc.state()), after);
  }

  void deletingAnEntityTakesItsTracksAndUndoBringsThemBack() {
    Document doc;
    doc.reset(buildStarterScene(), {});
    animateCamera(doc);
    const EntityId cam = cameraOf(doc);
    const std::string animated = canonicalJson(doc.state());
    QVERIFY(ops::remove(doc, {cam}));
    QVERIFY(doc.state().sequence.bindings.empty());
    QVERIFY(doc.state().validate().empty());
    doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), animated);
  }

  void duplicatingCopiesTracks() {
    Document doc;
    doc.reset(buildStarterScene(), {});
    animateCamera(doc);
    const auto copies = ops::duplicate(doc, {cameraOf(doc)});
    QCOMPARE(copies.size(), size_t(1));
    const sequencer::Binding* b = doc.state().sequence.findBinding(copies[0]);
    QVERIFY(b);
    QCOMPARE(b->tracks, doc.state().sequence.findBinding(cameraOf(doc))->tracks);
  }

  void sequenceSurvivesTheFile() {
    QTemporaryDir dir;
    Document doc;
    doc.reset(buildStarterScene(), {});
    animateCamera(doc);
    const std::string path = dir.filePath("anim.hscene").toStdString();
    std::string error;
    QVERIFY2(saveScene(doc.state(), path, error), error.c_str());
    auto loaded = loadScene(path, error);
    QVERIFY2(loaded, error.c_str());
    QCOMPARE(loaded->sequence, doc.state().sequence);
    QCOMPARE(canonicalJson(*loaded), canonicalJson(doc.state()));
  }

  void animatedStateAppliesValuesExactlyAtKeys() {
    Document doc;
    doc.reset(buildStarterScene(), {});
    animateCamera(doc);
    const auto compiled = compileSequence(doc.state());
    const EntityId cam = cameraOf(doc);
    std::vector<std::string> warnings;
    const SceneState at0 = animatedState(doc.state(), compiled, 0.0, &warnings);
    const SceneState at2 = animatedState(doc.state(), compiled, 2.0, &warnings);
    const SceneState at1 = animatedState(doc.state(), compiled, 1.0, &warnings);
    QVERIFY2(warnings.empty(), warnings.empty() ? "" : warnings.front().c_str());
    QCOMPARE(at0.find(cam)->camera->verticalFovDeg, 50.0);
    QCOMPARE(at2.find(cam)->camera->verticalFovDeg, 30.0);
    QCOMPARE(at2.find(cam)->transform.translation, glm::dvec3(10, -12, 4));
    QCOMPARE(at1.find(cam)->transform.translation, glm::dvec3(5, -12, 4));  // linear key
    QVERIFY(at0.find(cam)->visible);
    QVERIFY(!at1.find(cam)->visible);
    // The document itself is untouched: animation is evaluated, not stored.
    QCOMPARE(doc.state().find(cam)->camera->verticalFovDeg, Camera{}.verticalFovDeg);
  }

  void badTracksAreReportedNotApplied() {
    Document doc;
    doc.reset(buildStarterScene(), {});
    {
      Edit e(doc, "Bad tracks");
      const EntityId sun = doc.state().findByName("Sun");
      sequencer::Binding b;
      b.entity = sun;
      sequencer::ScalarTrack t = fovTrack();  // a camera property on a light
      b.tracks.push_back(t);
      sequencer::ScalarTrack u = fovTrack();
      u.property = "light.no_such_field";
      b.tracks.push_back(u);
      sequencer::ScalarTrack wrong = fovTrack();
      wrong.property = "transform.translation";  // a scalar track on a vector field
      b.tracks.push_back(wrong);
      e.sequence().bindings.push_back(b);
      sequencer::Binding ghost;
      ghost.entity = 999;
      ghost.tracks.push_back(fovTrack());
      e.sequence().bindings.push_back(ghost);
      e.commit();
    }
    std::vector<std::string> warnings;
    const SceneState s = animatedState(doc.state(), compileSequence(doc.state()), 1.0, &warnings);
    QCOMPARE(warnings.size(), size_t(4));
    QCOMPARE(s.find(doc.state().findByName("Sun"))->transform, doc.state().find(doc.state().findByName("Sun"))->transform);
  }

  void focalLengthIsTheFieldOfViewSeenDifferently() {
    Entity e;
    e.camera = Camera{};
    const EntityField* focal = findEntityField("camera.focal_length_mm");
    QVERIFY(focal);
    focal->set(e, FieldValue(50.0));
    // 24 mm sensor height at 50 mm: 2 atan(12/50) = 26.99 degrees.
    QVERIFY(std::abs(e.camera->verticalFovDeg - 26.9914) < 1e-3);
    QVERIFY(std::abs(std::get<double>(focal->get(e)) - 50.0) < 1e-9);
    QVERIFY(!focal->serialized);
  }
};

QTEST_GUILESS_MAIN(TestSceneSequence)
#include "test_scene_sequence.moc"
