// Tracks on material fields and scene settings (scene/object_tracks.h):
// evaluated as a pure function of time through the fields' setters (held to
// their declared ranges), keyed through ops::setKeys, saved in the
// description (sequence format 2), checked and clamped on load, and deleted
// with their material in one undo step.
#include <QtTest>

#include <cmath>

#include "scene/animation.h"
#include "scene/demo_scene.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/material_ops.h"
#include "scene/object_tracks.h"
#include "scene/scene_json.h"
#include "scene/sequence_edits.h"
#include "sequencer/key_edit.h"
#include "sequencer/sequence_json.h"

using namespace hs;
using namespace hs::scene;

namespace {

// A document with one standalone material "Rock" (in no mesh slot) and a camera.
MaterialId addRock(Document& doc) {
  Edit e(doc, "add");
  Material m;
  m.name = "Rock";
  m.roughness = 0.5f;
  const MaterialId id = e.addMaterial(m);
  Entity cam;
  cam.name = "Cam";
  cam.camera = Camera{};
  e.addEntity(cam);
  e.commit();
  return id;
}

AnimTarget target(const std::string& property) {
  std::string error;
  const auto t = animationTarget(property, error);
  if (!t) qFatal("%s", error.c_str());
  return *t;
}

void key(Document& doc, uint64_t who, const std::string& property, double t, sequencer::PropertyValue v,
         sequencer::Interpolation interp = sequencer::Interpolation::Linear) {
  std::string error;
  QVERIFY2(ops::setKeys(doc, {{who, target(property), v}}, t, interp, "key", {}, &error), error.c_str());
}

}  // namespace

class TestSceneObjectTracks : public QObject {
  Q_OBJECT

 private slots:
  void targetsAreDistinctFromEntities() {
    // Material 3 and entity 3 are different bindings; the tags never collide
    // with ids the file format allows (below 2^53).
    QVERIFY(materialTarget(3) != 3);
    QCOMPARE(sequencer::targetKind(3), sequencer::TargetKind::Entity);
    QCOMPARE(sequencer::targetKind(materialTarget(3)), sequencer::TargetKind::Material);
    QCOMPARE(sequencer::targetMaterial(materialTarget(3)), uint64_t(3));
    QCOMPARE(sequencer::targetKind(settingsTarget()), sequencer::TargetKind::Settings);
    QCOMPARE(sequencer::targetKind(uint64_t(1) << 53), sequencer::TargetKind::Entity);
  }

  void materialAndSettingsAnimate() {
    Document doc;
    const MaterialId rock = addRock(doc);
    key(doc, materialTarget(rock), "material.roughness", 0.0, 0.1);
    key(doc, materialTarget(rock), "material.roughness", 2.0, 0.9);
    key(doc, materialTarget(rock), "material.emission", 0.0, glm::dvec3(0.0));
    key(doc, materialTarget(rock), "material.emission", 4.0, glm::dvec3(1.0, 0.5, 0.0));
    key(doc, settingsTarget(), "settings.fog_density", 0.0, 0.001);
    key(doc, settingsTarget(), "settings.fog_density", 10.0, 0.003);
    key(doc, settingsTarget(), "settings.exposure_ev100", 0.0, 14.0);
    key(doc, settingsTarget(), "settings.exposure_ev100", 1.0, 12.0, sequencer::Interpolation::Cubic);
    // One binding each, named after the material and "Settings".
    const sequencer::Binding* mb = doc.state().sequence.findBinding(materialTarget(rock));
    QVERIFY(mb);
    QCOMPARE(mb->label, std::string("Rock"));
    QCOMPARE(mb->tracks.size(), size_t(2));
    QCOMPARE(doc.state().sequence.findBinding(settingsTarget())->label, std::string("Settings"));
    // The document itself is unchanged: only the evaluated state moves.
    QCOMPARE(doc.state().findMaterial(rock)->roughness, 0.5f);

    const auto compiled = compileSequence(doc.state());
    for (double t : {0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 7.5, 12.0}) {
      std::vector<std::string> warnings;
      const SceneState s = animatedState(doc.state(), compiled, t, &warnings);
      QVERIFY2(warnings.empty(), warnings.empty() ? "" : warnings.front().c_str());
      // Linear keys: the straight line between them, held after the last.
      const double u = std::clamp(t / 2.0, 0.0, 1.0);
      QCOMPARE(double(s.findMaterial(rock)->roughness), double(float(0.1 + (0.9 - 0.1) * u)));
      const double e = std::clamp(t / 4.0, 0.0, 1.0);
      QVERIFY(std::abs(double(s.findMaterial(rock)->emission.y) - 0.5 * e) < 1e-6);
      const double f = std::clamp(t / 10.0, 0.0, 1.0);
      QVERIFY(std::abs(double(s.settings.fogDensity) - (0.001 + 0.002 * f)) < 1e-8);
      // Cubic with flat ends: exactly the keys at the keys, between them inside.
      if (t == 0.0) QCOMPARE(s.settings.exposureEv100, 14.0f);
      if (t >= 1.0) QCOMPARE(s.settings.exposureEv100, 12.0f);
      if (t == 0.5) QVERIFY(std::abs(double(s.settings.exposureEv100) - 13.0) < 1e-5);  // smoothstep midpoint
      // Other fields untouched.
      QCOMPARE(s.findMaterial(rock)->opacity, 1.0f);
      QCOMPARE(s.settings.fogHeight, doc.state().settings.fogHeight);
    }
    // Pure: evaluating out of order gives the same values.
    const SceneState a = animatedState(doc.state(), compiled, 1.25);
    (void)animatedState(doc.state(), compiled, 9.0);
    const SceneState b = animatedState(doc.state(), compiled, 1.25);
    QCOMPARE(a.findMaterial(rock)->roughness, b.findMaterial(rock)->roughness);
    QCOMPARE(a.settings.fogDensity, b.settings.fogDensity);
  }

  void evaluationHoldsTheDeclaredRange() {
    Document doc;
    const MaterialId rock = addRock(doc);
    // Keys set past the range without the checks (a script editing the
    // sequence value): the setter clamps what the renderer sees.
    Edit e(doc, "raw");
    sequencer::Binding b{materialTarget(rock), "Rock", {}, std::nullopt};
    sequencer::ScalarTrack opacity{"material.opacity", {}};
    sequencer::ScalarKey k0, k1;
    k0.time = 0.0;
    k0.value = 0.5;
    k1.time = 1.0;
    k1.value = 3.0;
    k0.interpolation = sequencer::Interpolation::Linear;
    opacity.keys = {k0, k1};
    b.tracks.push_back(opacity);
    e.sequence().bindings.push_back(b);
    e.commit();
    const auto compiled = compileSequence(doc.state());
    QCOMPARE(animatedState(doc.state(), compiled, 0.0).findMaterial(rock)->opacity, 0.5f);
    QCOMPARE(animatedState(doc.state(), compiled, 0.1).findMaterial(rock)->opacity, 0.75f);
    QCOMPARE(animatedState(doc.state(), compiled, 0.5).findMaterial(rock)->opacity, 1.0f);  // 1.75 held to 1
    QCOMPARE(animatedState(doc.state(), compiled, 1.0).findMaterial(rock)->opacity, 1.0f);
  }

  void keysAreCheckedWhenSet() {
    Document doc;
    const MaterialId rock = addRock(doc);
    std::string error;
    QVERIFY(!animationTarget("material.model", error));  // an enum: not animatable
    QVERIFY(error.find("cannot be animated") != std::string::npos);
    QVERIFY(!animationTarget("material.no_such", error));
    QVERIFY(!animationTarget("settings.fog_mode", error));
    QVERIFY(animationTarget("settings.ao_strength", error));
    QVERIFY(!parseKeyValue(target("material.roughness"), "1.5", error));
    QVERIFY(error.find("out of range") != std::string::npos);
    QCOMPARE(std::get<double>(*parseKeyValue(target("settings.fog_density"), "0.01", error)), 0.01);
    // A material the scene lacks, or a settings field on a material binding: refused, nothing changes.
    const size_t steps = size_t(doc.undoStack()->count());
    QVERIFY(!ops::setKeys(doc, {{materialTarget(rock + 10), target("material.roughness"), 0.3}}, 0.0, {}, "k", {},
                          &error));
    QVERIFY(error.find("no material") != std::string::npos);
    QVERIFY(!ops::setKeys(doc, {{materialTarget(rock), target("settings.fog_density"), 0.3}}, 0.0, {}, "k", {},
                          &error));
    QVERIFY(!ops::setKeys(doc, {{materialTarget(rock), target("material.roughness"), glm::dvec3(1.0)}}, 0.0, {},
                          "k", {}, &error));
    QCOMPARE(size_t(doc.undoStack()->count()), steps);
    QVERIFY(doc.state().sequence.bindings.empty());
  }

  void savedAndReadBack() {
    Document doc;
    const MaterialId rock = addRock(doc);
    // Entity-only sequences stay format 1 (older builds read them).
    key(doc, doc.state().findByName("Cam"), "camera.fov_deg", 0.0, 40.0);
    QCOMPARE(sceneToJson(doc.state())["sequence"]["version"].get<int>(), 1);
    key(doc, materialTarget(rock), "material.roughness", 1.0, 0.25);
    key(doc, settingsTarget(), "settings.fog_colour", 2.0, glm::dvec3(0.5, 0.6, 0.7));
    const Json j = sceneToJson(doc.state());
    QCOMPARE(j["sequence"]["version"].get<int>(), 2);
    const Json& bindings = j["sequence"]["bindings"];
    QCOMPARE(bindings.size(), size_t(3));
    QCOMPARE(bindings[1]["material"].get<uint64_t>(), uint64_t(rock));
    QVERIFY(!bindings[1].contains("entity"));
    QCOMPARE(bindings[2]["settings"].get<bool>(), true);
    std::string error;
    bool notJson = false;
    std::vector<std::string> warnings;
    const auto back = sceneFromJsonText(writeJson(j), error, notJson, &warnings);
    QVERIFY2(back, error.c_str());
    QVERIFY(warnings.empty());
    QVERIFY(back->sequence == doc.state().sequence);
  }

  void badTracksAreDroppedOnLoadWithAMessage() {
    Document doc;
    const MaterialId rock = addRock(doc);
    key(doc, doc.state().findByName("Cam"), "camera.fov_deg", 0.0, 40.0);
    key(doc, materialTarget(rock), "material.roughness", 1.0, 0.25);
    key(doc, materialTarget(rock), "material.opacity", 1.0, 0.5);
    key(doc, settingsTarget(), "settings.fog_density", 2.0, 0.002);
    Json j = sceneToJson(doc.state());
    Json& bindings = j["sequence"]["bindings"];
    // A track of a material that is not there, an unknown material field,
    // an enum field, an out-of-range key, an unknown settings field.
    Json gone = bindings[1];
    gone["material"] = 99;
    gone["label"] = "Gone";
    bindings.push_back(gone);
    bindings[1]["tracks"][0]["property"] = "material.roughnes";
    bindings[1]["tracks"][1]["keys"][0]["v"] = 5.0;  // opacity 5
    bindings[2]["tracks"].push_back(bindings[2]["tracks"][0]);
    bindings[2]["tracks"][1]["property"] = "settings.fog_mode";
    std::string error;
    bool notJson = false;
    std::vector<std::string> warnings;
    const auto s = sceneFromJsonText(writeJson(j), error, notJson, &warnings);
    QVERIFY2(s, error.c_str());
    auto said = [&](const std::string& a, const std::string& b) {
      for (const std::string& w : warnings)
        if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
      return false;
    };
    QVERIFY2(said("'Gone' (#99)", "no material 99"), qPrintable(QString::number(warnings.size())));
    QVERIFY(said("'Rock'", "material.roughnes: no such animatable material field"));
    QVERIFY(said("settings track", "settings.fog_mode"));
    QVERIFY(said("material 'Rock'", "material.opacity key at frame 60: 5"));
    // The rest loaded: the camera's track, the opacity track (clamped to 1),
    // the settings' fog density; the bad ones are gone.
    QVERIFY(s->sequence.findBinding(s->findByName("Cam")));
    const sequencer::Binding* mb = s->sequence.findBinding(materialTarget(rock));
    QVERIFY(mb);
    QCOMPARE(mb->tracks.size(), size_t(1));
    QCOMPARE(std::get<sequencer::ScalarTrack>(mb->tracks[0]).keys[0].value, 1.0);
    QCOMPARE(s->sequence.findBinding(settingsTarget())->tracks.size(), size_t(1));
    QVERIFY(!s->sequence.findBinding(materialTarget(99)));
    QCOMPARE(s->findMaterial(rock)->name, std::string("Rock"));
  }

  void newerBindingKindsNeedVersion2() {
    // A version-1 sequence naming a material is not what version 1 means:
    // the entity is missing there, and the message says so.
    std::string error;
    QVERIFY(!sequencer::sequenceFromJsonText(
        R"({"format":"hybridscape-sequence","version":1,"rate":[60,1],"start":0,"end":9,
            "bindings":[{"material":3,"tracks":[]}]})",
        error));
    QVERIFY2(error.find("bindings[0].entity") != std::string::npos, error.c_str());
    QVERIFY(!sequencer::sequenceFromJsonText(
        R"({"format":"hybridscape-sequence","version":2,"rate":[60,1],"start":0,"end":9,
            "bindings":[{"material":3,"entity":2,"tracks":[]}]})",
        error));
    QVERIFY2(error.find("one target") != std::string::npos, error.c_str());
    QVERIFY(!sequencer::sequenceFromJsonText(
        R"({"format":"hybridscape-sequence","version":2,"rate":[60,1],"start":0,"end":9,
            "bindings":[{"settings":false,"tracks":[]}]})",
        error));
  }

  void deletingAMaterialTakesItsTracksAndUndoBringsThemBack() {
    Document doc;
    const MaterialId rock = addRock(doc);
    key(doc, materialTarget(rock), "material.roughness", 0.0, 0.2);
    key(doc, materialTarget(rock), "material.roughness", 1.0, 0.4);
    key(doc, settingsTarget(), "settings.ao_strength", 1.0, 2.0);
    const sequencer::Sequence before = doc.state().sequence;
    const int steps = doc.undoStack()->count();
    std::string error;
    QVERIFY2(ops::removeMaterial(doc, rock, error), error.c_str());
    QCOMPARE(doc.undoStack()->count(), steps + 1);  // one step
    QVERIFY(!doc.state().findMaterial(rock));
    QVERIFY(!doc.state().sequence.findBinding(materialTarget(rock)));
    QVERIFY(doc.state().sequence.findBinding(settingsTarget()));  // other tracks stay
    doc.undoStack()->undo();
    QVERIFY(doc.state().findMaterial(rock));
    QVERIFY(doc.state().sequence == before);
    doc.undoStack()->redo();
    QVERIFY(!doc.state().sequence.findBinding(materialTarget(rock)));
    // A material a mesh draws with is refused, naming the asset.
    Edit e(doc, "asset");
    MeshAsset a;
    a.name = "Scan";
    const MaterialId used = e.addMaterial(Material{.name = "Scan / default"});
    a.materialSlots = {used};
    e.addAsset(a);
    e.commit();
    QVERIFY(!ops::removeMaterial(doc, used, error));
    QVERIFY2(error.find("'Scan'") != std::string::npos, error.c_str());
  }

  void keyEditsWorkOnObjectTracks() {
    // KeyRef addresses material and settings keys like an entity's: move,
    // copy/paste and delete need nothing of their own.
    Document doc;
    const MaterialId rock = addRock(doc);
    key(doc, materialTarget(rock), "material.roughness", 1.0, 0.2);
    key(doc, settingsTarget(), "settings.fog_density", 1.0, 0.004);
    sequencer::Sequence seq = doc.state().sequence;
    const std::vector<sequencer::KeyRef> all = sequencer::allKeys(seq);
    QCOMPARE(all.size(), size_t(2));
    sequencer::moveKeys(seq, all, 0.5);
    QCOMPARE(sequencer::keyTimes(seq, materialTarget(rock), "material.roughness").front(), 1.5);
    QCOMPARE(sequencer::keyTimes(seq, settingsTarget(), "settings.fog_density").front(), 1.5);
    const auto clip = sequencer::copyKeys(seq, all);
    sequencer::pasteKeys(seq, clip, 4.0);
    QCOMPARE(sequencer::keyTimes(seq, materialTarget(rock), "material.roughness").size(), size_t(2));
    QCOMPARE(sequencer::removeKeys(seq, sequencer::allKeys(seq)), size_t(4));
    QVERIFY(seq.bindings.empty());
  }

  void demoAnimatesTheParallaxAndTheFog() {
    std::string error;
    const auto demo = buildDemoScene(error);
    QVERIFY2(demo, error.c_str());
    const MaterialId slab = demo->findMaterialByName("Rock slab (parallax) / surface");
    QVERIFY(slab != kNoMaterial);
    QVERIFY(demo->sequence.findBinding(materialTarget(slab)));
    QVERIFY(demo->sequence.findBinding(settingsTarget()));
    const auto compiled = compileSequence(*demo);
    // Frame 0 is the scene as placed (un-animated renders, the goldens, see
    // the same materials and settings).
    const SceneState at0 = animatedState(*demo, compiled, 0.0);
    QVERIFY(at0.materials == demo->materials);
    QVERIFY(at0.settings == demo->settings);
    const SceneState at5 = animatedState(*demo, compiled, 5.0);
    QCOMPARE(at5.findMaterial(slab)->heightScale, 0.01f);
    const SceneState at10 = animatedState(*demo, compiled, 10.0);
    QCOMPARE(at10.findMaterial(slab)->heightScale, demo->findMaterial(slab)->heightScale);
    QCOMPARE(at10.settings.fogK2, float(1.0 / 200.0));
    QVERIFY(at5.settings.fogK2 > demo->settings.fogK2 && at5.settings.fogK2 < at10.settings.fogK2);
  }
};

QTEST_GUILESS_MAIN(TestSceneObjectTracks)
#include "test_scene_object_tracks.moc"
