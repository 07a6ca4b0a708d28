// Physical light units (scene/light_units.h): the candela conversions
// against an independent integral, the reference exposure, files of format
// 5 (relative units, an exposure multiplier) and of format 7 (exposure
// against EV100 15.2, the BRDF's 1/π in the lights) converted so that they
// render as the builds that wrote them rendered them
// (tests/data/file/README.md).
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <filesystem>

#include <glm/gtc/constants.hpp>

#include "cli_runner.h"
#include "image_compare.h"
#include "scene/hscene_file.h"
#include "scene/light_units.h"
#include "scene/scene_json.h"
#include "sequencer/binding_target.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

namespace {
// The solid angle of a cone of half angle `half`, summed over thin rings
// (2π sin φ dφ), not from the closed form light_units.cpp uses.
double coneSolidAngle(double half) {
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double phi = (i + 0.5) * half / n;
    sum += 2.0 * glm::pi<double>() * std::sin(phi) * (half / n);
  }
  return sum;
}
}  // namespace

class LightUnitsTest : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

 private slots:
  // A light's candela times the solid angle it shines into is its power.
  void candelaTimesSolidAngleIsPower() {
    Light point;
    point.type = Light::Type::Point;
    point.intensity = 1000.0f;
    QVERIFY(std::abs(luminousIntensityCandela(point) * coneSolidAngle(glm::pi<double>()) - 1000.0) < 1e-3);
    Light spot;
    spot.type = Light::Type::Spot;
    spot.intensity = 1000.0f;
    for (float outer : {2.0f, 45.0f, 90.0f, 170.0f}) {
      spot.outerConeDeg = outer;
      const double power = luminousIntensityCandela(spot) * coneSolidAngle(glm::radians(double(outer)) * 0.5);
      QVERIFY2(std::abs(power - 1000.0) < 1e-2, qPrintable(QString("outer %1: %2 lm").arg(outer).arg(power)));
    }
    // The inner cone shapes the edge, not the power.
    spot.outerConeDeg = 60.0f;
    const double before = luminousIntensityCandela(spot);
    spot.innerConeDeg = 10.0f;
    QCOMPARE(luminousIntensityCandela(spot), before);
    Light sun;
    sun.intensity = 100000.0f;
    QCOMPARE(luminousIntensityCandela(sun), 100000.0);
  }

  // Filament's exposure: one scene unit is 1.2 · 2^EV100 cd/m² at the
  // reference EV100, 15.2 − log2 π, and each EV100 step halves the image.
  void exposure() {
    QCOMPARE(exposureMultiplier(SceneSettings{}.exposureEv100), 1.0);
    QVERIFY(std::abs(exposureMultiplier(SceneSettings{}.exposureEv100 + 1.0f) - 0.5) < 1e-6);
    QVERIFY(std::abs(kReferenceEv100 - (15.2 - std::log2(glm::pi<double>()))) < 1e-12);
    QVERIFY(std::abs(SceneSettings{}.exposureEv100 - 13.5485f) < 1e-4f);
    QVERIFY(std::abs(sceneUnitsPerNit() * 1.2 * std::pow(2.0, 13.548503870527680) - 1.0) < 1e-12);
    // A light's result in scene units is what it was before the shaders
    // applied the BRDF's 1/π: lux/π in this unit is lux in 1/(1.2 · 2^15.2).
    QVERIFY(std::abs(sceneUnitsPerNit() / glm::pi<double>() * 1.2 * std::pow(2.0, 15.2) - 1.0) < 1e-12);
    // The default sun on a white surface facing it (E/π): 100 000 lux at the
    // default exposure, within 0.7% of the 2.2 the default sun gave before
    // physical units.
    const glm::vec3 c = lightRadiometricColor(Light{}) / Light{}.color / glm::pi<float>();
    QVERIFY2(std::abs(c.x / 2.2f - 1.0f) < 0.007f, qPrintable(QString::number(double(c.x))));
  }

  // Formats 6 and 7 took exposures against EV100 15.2 (the shaders folded
  // the BRDF's 1/π into the lights): their exposure and the keys of its
  // track move by −log2 π on load, lights keep their values, and format 8
  // is read as written.
  void format6And7ExposureMoves() {
    SceneState s;
    Entity sun;
    sun.id = 1;
    sun.name = "Sun";
    sun.light = Light{};
    sun.light->intensity = 70000.0f;
    s.entities = {{1, sun}};
    s.roots = {1};
    s.settings.exposureEv100 = 14.25f;
    sequencer::Binding b{sequencer::kSettingsTarget, "Settings", {}, std::nullopt};
    sequencer::ScalarTrack track;
    track.property = "settings.exposure_ev100";
    for (auto [t, v] : {std::pair{0.0, 14.0}, std::pair{2.0, 16.5}, std::pair{3.0, -9.0}}) {
      sequencer::ScalarKey k;
      k.time = t;
      k.value = v;
      k.setSlope(0.25);  // user tangents: kept as written
      track.keys.push_back(k);
    }
    b.tracks.push_back(track);
    s.sequence.bindings = {b};
    const double shift = std::log2(glm::pi<double>());
    for (int version : {6, 7, 8}) {
      Json json = sceneToJson(s);
      json["version"] = version;
      std::string error;
      const auto loaded = sceneFromJson(json, error);
      QVERIFY2(loaded, error.c_str());
      const double moved = version < kFirstPhysicalBrdfFormat ? shift : 0.0;
      QVERIFY(std::abs(double(loaded->settings.exposureEv100) - (14.25 - moved)) < 1e-5);
      QCOMPARE(loaded->find(1)->light->intensity, 70000.0f);
      const sequencer::Binding* lb = loaded->sequence.findBinding(sequencer::kSettingsTarget);
      QVERIFY(lb && lb->tracks.size() == 1);
      const auto& keys = std::get<sequencer::ScalarTrack>(lb->tracks[0]).keys;
      QCOMPARE(keys.size(), size_t(3));
      QVERIFY(std::abs(keys[0].value - (14.0 - moved)) < 1e-12);
      QVERIFY(std::abs(keys[1].value - (16.5 - moved)) < 1e-12);
      // Held at the field's lower end (−10) rather than below it.
      QVERIFY(std::abs(keys[2].value - std::max(-9.0 - moved, -10.0)) < 1e-12);
      QCOMPARE(keys[1].inSlope, 0.25);  // a shift leaves the slopes alone
      QCOMPARE(keys[1].outSlope, 0.25);
      // The same frame: the multiplier against this build's reference is the
      // old one against 15.2.
      if (version < kFirstPhysicalBrdfFormat)
        QVERIFY(std::abs(exposureMultiplier(loaded->settings.exposureEv100) - std::exp2(15.2 - 14.25)) < 1e-5);
    }
    // A format-7 file without the key meant its default, 15.2: this build's
    // default (multiplier 1), not moved a second time.
    Json json = sceneToJson(s);
    json["version"] = 7;
    json["settings"].erase("exposure_ev100");
    std::string error;
    const auto loaded = sceneFromJson(json, error);
    QVERIFY2(loaded, error.c_str());
    QCOMPARE(loaded->settings.exposureEv100, SceneSettings{}.exposureEv100);
    QCOMPARE(exposureMultiplier(loaded->settings.exposureEv100), 1.0);
  }

  // A real format-7 file (tests/data/file/README.md) written and rendered
  // by the build before format 8: its values moved as above, and the
  // program renders two frames of it (the keyed exposure at 0 and 1 s) as
  // that build did, within 2 of 255.
  void format7RendersAsBefore() {
    std::string error;
    const auto old = loadScene(HS_TEST_DATA_DIR "/file/format7_lights.hscene", error);
    QVERIFY2(old, error.c_str());
    const double shift = std::log2(glm::pi<double>());
    QVERIFY(std::abs(double(old->settings.exposureEv100) - (double(15.8f) - shift)) < 1e-5);
    QCOMPARE(old->find(old->findByName("Sun"))->light->intensity, 80000.0f);
    QCOMPARE(old->find(old->findByName("Lamp"))->light->intensity, 400000.0f);
    QCOMPARE(old->find(old->findByName("Spot"))->light->intensity, 800000.0f);
    const sequencer::Binding* b = old->sequence.findBinding(sequencer::kSettingsTarget);
    QVERIFY(b && b->tracks.size() == 1);
    const auto& keys = std::get<sequencer::ScalarTrack>(b->tracks[0]).keys;
    QCOMPARE(keys.size(), size_t(2));
    QVERIFY(std::abs(keys[0].value - (15.8 - shift)) < 1e-9);
    QVERIFY(std::abs(keys[1].value - (16.6 - shift)) < 1e-9);
    // Saved again it is of this format and is not moved a second time.
    const std::string again = (fs::path(tmp_.path().toStdString()) / "again7.hscene").string();
    QVERIFY2(saveScene(*old, again, error), error.c_str());
    QCOMPARE(sceneFileVersion(again), kSceneFormatVersion);
    const auto reread = loadScene(again, error);
    QVERIFY2(reread, error.c_str());
    QCOMPARE(reread->settings.exposureEv100, old->settings.exposureEv100);

    const QString file = tmp_.filePath("format7_lights.hscene");
    QFile::remove(file);
    QVERIFY(QFile::copy(HS_TEST_DATA_DIR "/file/format7_lights.hscene", file));
    QFile::setPermissions(file, QFile::ReadOwner | QFile::WriteOwner);
    const QString pattern = tmp_.filePath("format7_lights_%05d.png");
    const test::CliRun r = test::runCli({"render", file, "--frames", "0,60", "--layout", "mono", "--out", pattern,
                                         "--size", "160x90", "--no-grid", "--overwrite"},
                                        tmp_.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    for (const char* frame : {"00000", "00060"}) {
      const std::string name = std::string("format7_lights_") + frame + ".png";
      test::Rgba8Image now, before;
      QVERIFY(test::readPng(tmp_.filePath(QString::fromStdString(name)).toStdString(), now));
      QVERIFY(test::readPng(std::string(HS_TEST_DATA_DIR "/file/") + name, before));
      const test::CompareResult c = test::compareImages(now, before, 2);
      QVERIFY2(c.sizeMatches && c.maxChannelDiff <= 2, qPrintable(QString::fromStdString(name + ": " + c.summary())));
    }
  }

  // The fixtures were written and rendered by the build before physical
  // units (commit 6aac0a7): a sun of 3.1 with a keyed intensity and
  // exposure 0.7; a point light of 12 at 1 m with exposure 1.6.
  void format5ValuesConvert() {
    std::string error;
    const auto sun = loadScene(HS_TEST_DATA_DIR "/file/format5_sun.hscene", error);
    QVERIFY2(sun, error.c_str());
    const Entity* s = sun->find(sun->findByName("Sun"));
    QVERIFY(s && s->light && s->light->type == Light::Type::Sun);
    const double luxPerOld = 1.2 * std::pow(2.0, 15.2);
    QVERIFY(std::abs(double(s->light->intensity) / (3.1 * luxPerOld) - 1.0) < 1e-6);
    QVERIFY(std::abs(exposureMultiplier(sun->settings.exposureEv100) - 0.7) < 1e-6);
    // The keyed intensity: values (and so the curve) in lux too.
    const sequencer::Binding* b = sun->sequence.findBinding(s->id);
    QVERIFY(b && b->tracks.size() == 1);
    const auto& keys = std::get<sequencer::ScalarTrack>(b->tracks[0]).keys;
    QCOMPARE(keys.size(), size_t(2));
    QVERIFY(std::abs(keys[0].value / (3.1 * luxPerOld) - 1.0) < 1e-9);
    QVERIFY(std::abs(keys[1].value / (1.0 * luxPerOld) - 1.0) < 1e-9);

    const auto point = loadScene(HS_TEST_DATA_DIR "/file/format5_point.hscene", error);
    QVERIFY2(point, error.c_str());
    const Entity* p = point->find(point->findByName("Sun"));  // the starter sun, made a point light
    QVERIFY(p && p->light && p->light->type == Light::Type::Point);
    // 12 at 1 m: 12 · luxPerOld cd, 4π times that in lumens.
    QVERIFY(std::abs(double(p->light->intensity) / (4.0 * glm::pi<double>() * 12.0 * luxPerOld) - 1.0) < 1e-6);
    QVERIFY(std::abs(luminousIntensityCandela(*p->light) / (12.0 * luxPerOld) - 1.0) < 1e-6);
    QVERIFY(std::abs(exposureMultiplier(point->settings.exposureEv100) - 1.6) < 1e-6);
    // Saved again, the file is of this format and holds the new values.
    const std::string again = (fs::path(tmp_.path().toStdString()) / "again.hscene").string();
    QVERIFY2(saveScene(*point, again, error), error.c_str());
    QCOMPARE(sceneFileVersion(again), kSceneFormatVersion);
    const auto reread = loadScene(again, error);
    QVERIFY2(reread, error.c_str());
    QCOMPARE(reread->find(p->id)->light->intensity, p->light->intensity);
    QCOMPARE(reread->settings.exposureEv100, point->settings.exposureEv100);
  }

  // Format 7 reads each light's casts_shadows; before it a sun cast
  // whenever settings.shadows was on, so an older file's suns keep casting
  // and its spot keeps what was stored; a format-7 file keeps a sun off.
  void format6SunsKeepTheirShadows() {
    SceneState s;
    Entity sun;
    sun.id = 1;
    sun.name = "Sun";
    sun.light = Light{};
    sun.light->castsShadows = false;
    Entity spot;
    spot.id = 2;
    spot.name = "Spot";
    spot.light = Light{};
    spot.light->type = Light::Type::Spot;
    spot.light->castsShadows = true;
    Entity plain = spot;
    plain.id = 3;
    plain.name = "Plain";
    plain.light->castsShadows = false;
    s.entities = {{1, sun}, {2, spot}, {3, plain}};
    s.roots = {1, 2, 3};
    for (int version : {6, 7}) {
      Json json = sceneToJson(s);
      json["version"] = version;
      std::string error;
      const auto loaded = sceneFromJson(json, error);
      QVERIFY2(loaded, error.c_str());
      QCOMPARE(loaded->find(1)->light->castsShadows, version < kFirstPerLightShadowsFormat);
      QCOMPARE(loaded->find(2)->light->castsShadows, true);
      QCOMPARE(loaded->find(3)->light->castsShadows, false);
    }
    // The format-5 fixture's sun too (it was written before the flag existed).
    std::string error;
    const auto old = loadScene(HS_TEST_DATA_DIR "/file/format5_sun.hscene", error);
    QVERIFY2(old, error.c_str());
    QVERIFY(old->find(old->findByName("Sun"))->light->castsShadows);
  }

  // The real program renders each fixture as the older build did: same
  // size, camera and settings, compared with the PNG that build wrote.
  void format5RendersAsBefore() {
    for (const char* name : {"format5_sun", "format5_point"}) {
      const QString file = tmp_.filePath(QString(name) + ".hscene");
      QFile::remove(file);
      QVERIFY(QFile::copy(QString(HS_TEST_DATA_DIR "/file/") + name + ".hscene", file));
      QFile::setPermissions(file, QFile::ReadOwner | QFile::WriteOwner);
      const QString out = tmp_.filePath(QString(name) + ".png");
      const test::CliRun r = test::runCli({"render", file, "--out", out, "--size", "160x90", "--no-grid"}, tmp_.path());
      QVERIFY2(r.code == 0, qPrintable(r.err));
      test::Rgba8Image now, before;
      QVERIFY(test::readPng(out.toStdString(), now));
      QVERIFY(test::readPng(std::string(HS_TEST_DATA_DIR "/file/") + name + ".png", before));
      // Float rounding of the converted values only: at most 2 of 255.
      const test::CompareResult c = test::compareImages(now, before, 2);
      QVERIFY2(c.sizeMatches && c.maxChannelDiff <= 2, qPrintable(QString(name) + ": " + QString::fromStdString(c.summary())));
    }
  }
};

QTEST_GUILESS_MAIN(LightUnitsTest)
#include "test_light_units.moc"
