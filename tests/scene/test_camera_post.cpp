// A camera's own post settings (scene/camera_post.h): which settings a
// camera may override, the fields that edit them (clamped as the scene's
// are), the settings a view through it renders with, the file (round trip,
// a key this build does not know, a value of the wrong type or out of
// range), undo, and a track on an override evaluated at its times.
#include <QtTest>

#include "scene/animation.h"
#include "scene/camera_post.h"
#include "scene/document.h"
#include "scene/operations.h"
#include "scene/scene_json.h"

using namespace hs;

namespace {

constexpr scene::EntityId kCamera = 7;

scene::SceneState oneCamera() {
  scene::SceneState s;
  scene::Entity c;
  c.id = kCamera;
  c.name = "Shot B";
  c.camera = scene::Camera{};
  s.entities.emplace(c.id, c);
  s.roots.push_back(c.id);
  return s;
}

const scene::EntityField& field(const char* path) {
  const scene::EntityField* f = scene::findEntityField(path);
  if (!f) qFatal("no field %s", path);
  return *f;
}

}  // namespace

class TestCameraPost : public QObject {
  Q_OBJECT
 private slots:
  // Every setting of the post chain, the exposure, the tone map and the
  // anti-aliasing, nothing else (shadows or fog are the scene's).
  void theOverridableSettingsAreThePostChain() {
    size_t post = 0;
    for (const scene::SettingsField& f : scene::settingsFields()) {
      const bool expected = f.key.rfind("post.", 0) == 0 || f.key == "exposure_ev100" || f.key == "tonemap" ||
                            f.key == "antialiasing";
      QCOMPARE(scene::cameraOverridable(f), expected);
      if (!expected) {
        QVERIFY(!scene::findEntityField("camera.post." + scene::cameraPostKey(f.key)));
        continue;
      }
      ++post;
      const scene::EntityField* e = scene::findEntityField("camera.post." + scene::cameraPostKey(f.key));
      QVERIFY2(e, f.key.c_str());
      QCOMPARE(e->label, f.label);
      QCOMPARE(int(e->type), int(f.type));
      QCOMPARE(scene::cameraPostSetting(scene::cameraPostKey(f.key)), &f);
    }
    QCOMPARE(scene::cameraPostFields().size(), post);
    QVERIFY(post > 40);
    QCOMPARE(scene::cameraPostKey("post.bloom.intensity"), std::string("bloom.intensity"));
    QCOMPARE(scene::cameraPostKey("tonemap"), std::string("tonemap"));
    QVERIFY(!scene::findEntityField("camera.post.shadows"));
    QVERIFY(!scene::findEntityField("camera.post.nothing"));
  }

  // Set through the setting's own setter: clamped to its range, a NaN
  // keeps what was there; get answers the default where there is no override.
  void anOverrideIsClampedAsTheSettingIs() {
    scene::SceneState s = oneCamera();
    scene::Entity& c = s.entities.at(kCamera);
    const scene::EntityField& intensity = field("camera.post.bloom.intensity");
    const scene::SettingsField& setting = *scene::findSettingsField("post.bloom.intensity");
    QCOMPARE(intensity.get(c), setting.get(scene::SceneSettings{}));
    QVERIFY(c.camera->post.empty());
    intensity.set(c, 1e9);
    QCOMPARE(std::get<double>(c.camera->post.at("bloom.intensity")), setting.max);
    intensity.set(c, std::numeric_limits<double>::quiet_NaN());
    QCOMPARE(std::get<double>(c.camera->post.at("bloom.intensity")), setting.max);
    QVERIFY(!scene::fieldValueProblem(intensity, std::numeric_limits<double>::quiet_NaN(), &c).empty());
    QVERIFY(!scene::fieldValueProblem(intensity, -1.0, &c).empty());
    // An entity without a camera is left alone.
    scene::Entity plain;
    intensity.set(plain, 0.5);
    QVERIFY(!plain.camera);
  }

  // The view's settings: the scene's with the camera's fields replaced,
  // the rest the scene's; the manual exposure yields to automatic exposure.
  void settingsThroughACamera() {
    scene::SceneState s = oneCamera();
    s.settings.tonemap = scene::Tonemap::Aces;
    s.settings.post.bloom = true;
    s.settings.post.bloomIntensity = 0.2f;
    s.settings.exposureEv100 = 13.0f;
    scene::Entity& c = s.entities.at(kCamera);
    QVERIFY(scene::samePostChain(scene::settingsFor(s, kCamera), s.settings));
    field("camera.post.tonemap").set(c, int64_t(scene::Tonemap::AgX));
    field("camera.post.bloom.intensity").set(c, 0.6);
    field("camera.post.exposure_ev100").set(c, 11.0);
    scene::SceneSettings v = scene::settingsFor(s, kCamera);
    QCOMPARE(v.tonemap, scene::Tonemap::AgX);
    QCOMPARE(v.post.bloomIntensity, 0.6f);
    QVERIFY(v.post.bloom);                // the scene's
    QCOMPARE(v.exposureEv100, 11.0f);     // manual exposure: the camera's
    QVERIFY(!scene::samePostChain(v, s.settings));
    QCOMPARE(scene::settingsFor(s, scene::kNoEntity), s.settings);  // a free view
    QCOMPARE(scene::settingsFor(s, 999), s.settings);               // no such entity
    // With automatic exposure on (the camera's or the scene's) the EV the
    // caller metered into the settings stands.
    field("camera.post.auto_exposure.enabled").set(c, true);
    s.settings.exposureEv100 = 9.5f;
    v = scene::settingsFor(s, kCamera);
    QVERIFY(v.post.autoExposure);
    QCOMPARE(v.exposureEv100, 9.5f);
    // Differing only in a setting no camera overrides: the same chain.
    scene::SceneSettings a = s.settings, b = s.settings;
    b.shadows = !a.shadows;
    QVERIFY(scene::samePostChain(a, b));
    b.post.grainIntensity += 0.1f;
    QVERIFY(!scene::samePostChain(a, b));
  }

  // Written as the camera's "post" object and read back equal; a key this
  // build does not know is dropped with a warning; a wrong type refuses
  // the file naming the value's path; out of range is clamped and named.
  void theFileKeepsOverrides() {
    scene::SceneState s = oneCamera();
    scene::Entity& c = s.entities.at(kCamera);
    field("camera.post.tonemap").set(c, int64_t(scene::Tonemap::PbrNeutral));
    field("camera.post.grade.lift").set(c, glm::dvec3(0.01, 0.0, -0.02));
    field("camera.post.grain.enabled").set(c, true);
    const Json j = scene::sceneToJson(s);
    const Json& post = j["entities"][0]["components"]["camera"]["post"];
    QCOMPARE(post["tonemap"].get<std::string>(), std::string("PBR Neutral"));
    QVERIFY(post["grain.enabled"].get<bool>());
    std::string error;
    std::optional<scene::SceneState> back = scene::sceneFromJson(j, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->entities.at(kCamera).camera->post, c.camera->post);
    QCOMPARE(scene::canonicalJson(*back), scene::canonicalJson(s));
    // No overrides: no "post" member (files of cameras without stay as they were).
    scene::SceneState plain = oneCamera();
    QVERIFY(!scene::sceneToJson(plain)["entities"][0]["components"]["camera"].contains("post"));

    Json unknown = j;
    unknown["entities"][0]["components"]["camera"]["post"]["lens_flare.intensity"] = 2.0;
    bool notJson = false;
    std::vector<std::string> warnings;
    back = scene::sceneFromJsonText(unknown.dump(), error, notJson, &warnings);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->entities.at(kCamera).camera->post, c.camera->post);
    QCOMPARE(warnings.size(), size_t(1));
    QVERIFY2(warnings[0].find("camera.post.lens_flare.intensity") != std::string::npos, warnings[0].c_str());
    QVERIFY2(warnings[0].find("Shot B") != std::string::npos, warnings[0].c_str());

    Json wrong = j;
    wrong["entities"][0]["components"]["camera"]["post"]["grain.enabled"] = "often";
    QVERIFY(!scene::sceneFromJson(wrong, error));
    QVERIFY2(error.find("entities[0].components.camera.post.grain.enabled") != std::string::npos, error.c_str());
    Json notObject = j;
    notObject["entities"][0]["components"]["camera"]["post"] = 3;
    QVERIFY(!scene::sceneFromJson(notObject, error));
    QVERIFY2(error.find("camera.post") != std::string::npos, error.c_str());

    Json far = j;
    far["entities"][0]["components"]["camera"]["post"]["bloom.intensity"] = 1e9;
    warnings.clear();
    back = scene::sceneFromJsonText(far.dump(), error, notJson, &warnings);
    QVERIFY2(back, error.c_str());
    QCOMPARE(std::get<double>(back->entities.at(kCamera).camera->post.at("bloom.intensity")),
             scene::findSettingsField("post.bloom.intensity")->max);
    QCOMPARE(warnings.size(), size_t(1));
    QVERIFY2(warnings[0].find("camera.post.bloom.intensity") != std::string::npos, warnings[0].c_str());
  }

  // Setting adds the override in one undo step; clearing removes it in
  // another; undo brings each back.
  void overridesAreUndoable() {
    scene::Document doc;
    doc.reset(oneCamera(), "camera_post.hscene");
    QVERIFY(scene::ops::setField(doc, kCamera, field("camera.post.vignette.intensity"), 0.4));
    QCOMPARE(doc.state().find(kCamera)->camera->post.size(), size_t(1));
    QVERIFY(!scene::ops::clearCameraPost(doc, kCamera, "bloom.intensity"));  // none to clear
    QVERIFY(scene::ops::clearCameraPost(doc, kCamera, "vignette.intensity"));
    QVERIFY(doc.state().find(kCamera)->camera->post.empty());
    doc.undoStack()->undo();
    // Held as the setting holds it (a float).
    QCOMPARE(std::get<double>(doc.state().find(kCamera)->camera->post.at("vignette.intensity")), double(0.4f));
    doc.undoStack()->undo();
    QVERIFY(doc.state().find(kCamera)->camera->post.empty());
  }

  // A track on "camera.post.bloom.intensity" sets the override at its times
  // (the camera had none), interpolated like any camera field.
  void aTrackAnimatesAnOverride() {
    scene::SceneState s = oneCamera();
    sequencer::ScalarTrack t;
    t.property = "camera.post.bloom.intensity";
    for (auto [time, value] : {std::pair{0.0, 0.0}, std::pair{2.0, 1.0}}) {
      sequencer::ScalarKey k;
      k.time = time;
      k.value = value;
      k.interpolation = sequencer::Interpolation::Linear;
      t.keys.push_back(k);
    }
    s.sequence.bindings = {sequencer::Binding{kCamera, "Shot B", {t}, std::nullopt}};
    const sequencer::CompiledSequence compiled = scene::compileSequence(s);
    std::vector<std::string> warnings;
    const scene::SceneState at = scene::animatedState(s, compiled, 0.5, &warnings);
    QVERIFY(warnings.empty());
    QCOMPARE(scene::settingsFor(at, kCamera).post.bloomIntensity, 0.25f);
    QVERIFY(s.entities.at(kCamera).camera->post.empty());  // the document's own state: none
    // The track survives the file.
    std::string error;
    QVERIFY(scene::sceneFromJson(scene::sceneToJson(s), error));
  }
};

QTEST_GUILESS_MAIN(TestCameraPost)
#include "test_camera_post.moc"
