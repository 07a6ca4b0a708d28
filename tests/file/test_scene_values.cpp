// Values checked once (scene/fields.cpp: each field's range and rule beside
// its declaration): the CLI refuses what makes no sense with the rule and
// leaves the file as it was; a file that holds such values opens clamped or
// repaired, with a warning naming the entity and the field. The cases are
// the robustness campaign's (docs/reliability.md).
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <string>

#include "cli_runner.h"
#include "file_bytes.h"
#include "hscene_sql.h"
#include "scene/hscene_file.h"
#include "core/json.h"
#include "scene/fields.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

class TestSceneValues : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString scene_;

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = test::newSceneWithCli("values.hscene", tmp_.path());
  }

  void cliRefusesValuesOutOfRange_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<int>("code");
    QTest::addColumn<QString>("named");
    const QString range = "Vertical field of view must be from 1 to 170";
    QTest::newRow("fov 0") << QStringList{"set", "Camera", "camera.fov_deg", "0"} << 1 << range;
    QTest::newRow("fov 1e308") << QStringList{"set", "Camera", "camera.fov_deg", "1e308"} << 1 << range;
    QTest::newRow("fov -1e308") << QStringList{"set", "Camera", "camera.fov_deg", "-1e308"} << 1 << range;
    QTest::newRow("far -1") << QStringList{"set", "Camera", "camera.far_m", "-1"} << 1
                            << "Far clip must be from 0.01 to 1e+08 m";
    QTest::newRow("far inside near") << QStringList{"set", "Camera", "camera.far_m", "0.05"} << 1
                                     << "Far clip must be greater than the near clip (0.1 m)";
    QTest::newRow("scale 0") << QStringList{"set", "Camera", "transform.scale", "0,0,0"} << 1
                             << "Scale must be non-zero on every axis";
    QTest::newRow("empty name") << QStringList{"set", "Camera", "entity.name", ""} << 1 << "Name must not be empty";
    QTest::newRow("exposure 40") << QStringList{"set", "settings.exposure_ev100", "40"} << 1
                                 << "Exposure (EV100) must be from -10 to 30 EV";
    QTest::newRow("intensity -1") << QStringList{"set", "Sun", "light.intensity", "-1"} << 1
                                  << "Intensity must be from 0 to 1e+12 lx (sun) or lm";
    QTest::newRow("intensity nan") << QStringList{"set", "Sun", "light.intensity", "nan"} << 1
                                   << "'nan' is not a finite number";
    QTest::newRow("cone 180") << QStringList{"set", "Sun", "light.outer_cone_deg", "180"} << 1
                              << "Outer cone must be from 0.1 to 179.9 °";
    QTest::newRow("cone 0") << QStringList{"set", "Sun", "light.inner_cone_deg", "0"} << 1
                            << "Inner cone must be from 0.1 to 179.9 °";
    QTest::newRow("inner beyond outer") << QStringList{"set", "Sun", "light.inner_cone_deg", "50"} << 1
                                        << "Inner cone must not exceed the outer cone (45 °)";
    QTest::newRow("key value fov 0") << QStringList{"key", "Camera", "camera.fov_deg", "5", "0"} << 1 << range;
    QTest::newRow("key frame 1e20") << QStringList{"key", "Camera", "camera.fov_deg", "99999999999999999999f", "40"}
                                    << 2 << "out of range (-2147483647 to 2147483647 frames)";
  }
  void cliRefusesValuesOutOfRange() {
    QFETCH(QStringList, args);
    QFETCH(int, code);
    QFETCH(QString, named);
    const std::string file = (fs::path(tmp_.path().toStdString()) / scene_.toStdString()).string();
    const std::string before = test::readFile(file);
    const test::CliRun r = test::runCli(args << scene_, tmp_.path());
    QCOMPARE(r.code, code);
    QCOMPARE(r.errLines().size(), 1);
    QVERIFY2(r.err.contains(named), qPrintable(r.err));
    QVERIFY2(test::readFile(file) == before, "a refused value changed the file");
  }

  // The same values written into a file behind the library's back.
  void loaderClampsAndWarns() {
    const std::string file = (fs::path(tmp_.path().toStdString()) / "hostile.hscene").string();
    fs::copy_file((fs::path(tmp_.path().toStdString()) / scene_.toStdString()), file);
    std::string json = test::readDescription(file);
    // The value of the first member `key`, replaced by `value`.
    const auto setMember = [&json](const std::string& key, const std::string& value) {
      const std::string head = "\"" + key + "\": ";
      const size_t at = json.find(head);
      QVERIFY2(at != std::string::npos, key.c_str());
      const size_t from = at + head.size();
      json.replace(from, json.find_first_of(",}\n", from) - from, value);
    };
    json.replace(json.find("\"name\": \"Camera\""), 16, "\"name\": \"\"");
    setMember("fov_deg", "0");
    setMember("far_m", "-1");
    setMember("exposure_ev100", "1e308");
    // A light's bad values: negative power, cones outside (0, 180) and the
    // inner cone beyond the outer one.
    setMember("intensity", "-5");
    setMember("inner_cone_deg", "170");
    setMember("outer_cone_deg", "-3");
    test::writeDescription(file, json);
    std::string error;
    LoadReport report;
    std::optional<SceneState> s = loadScene(file, error, nullptr, &report);
    QVERIFY2(s, error.c_str());
    const std::string all = [&] {
      std::string t;
      for (const auto& w : report.warnings) t += w + "\n";
      return t;
    }();
    QVERIFY2(all.find(file + ": entity 2 '': camera.fov_deg 0 must be from 1 to 170 °; now 1") != std::string::npos,
             all.c_str());
    QVERIFY2(all.find("camera.far_m -1 must be from 0.01 to 1e+08 m; now 0.01") != std::string::npos, all.c_str());
    QVERIFY2(all.find("camera.near_m 0.1 must be less than the far clip (0.01 m); now 1e-05") != std::string::npos,
             all.c_str());
    QVERIFY2(all.find("entity.name '' must not be empty; now 'Entity 2'") != std::string::npos, all.c_str());
    QVERIFY2(all.find("settings.exposure_ev100 1e+308 must be from -10 to 30 EV; now 30") != std::string::npos,
             all.c_str());
    QVERIFY2(all.find(file + ": entity 1 'Sun': light.intensity -5 must be from 0 to 1e+12 lx (sun) or lm; now 0") !=
                 std::string::npos,
             all.c_str());
    QVERIFY2(all.find("entity 1 'Sun': light.outer_cone_deg -3 must be from 0.1 to 179.9 °; now 0.1") != std::string::npos,
             all.c_str());
    QVERIFY2(all.find("entity 1 'Sun': light.inner_cone_deg 170 must not exceed the outer cone (0.1 °); now 0.1") !=
                 std::string::npos,
             all.c_str());
    const Entity* cam = s->find(2);
    QVERIFY(cam && cam->camera);
    QCOMPARE(cam->name, std::string("Entity 2"));
    QCOMPARE(cam->camera->verticalFovDeg, 1.0);
    QVERIFY(cam->camera->nearClip > 0.0 && cam->camera->nearClip < cam->camera->farClip);
    QCOMPARE(s->settings.exposureEv100, 30.0f);
    const Entity* sun = s->find(1);
    QVERIFY(sun && sun->light);
    QCOMPARE(sun->light->intensity, 0.0f);
    QCOMPARE(sun->light->innerConeDeg, 0.1f);
    QCOMPARE(sun->light->outerConeDeg, 0.1f);
    // A file with sound values opens without a warning.
    report = {};
    QVERIFY(loadScene((fs::path(tmp_.path().toStdString()) / scene_.toStdString()).string(), error, nullptr, &report));
    QVERIFY(report.warnings.empty());
  }

  // Keyed values are held to the same ranges: a key written into the file
  // behind the library's back is clamped on load, and the warning names the
  // entity, the field and the key's frame. (Was: loaded as written.)
  void loaderClampsKeyValuesAndWarns() {
    const fs::path dir = tmp_.path().toStdString();
    const std::string file = (dir / "hostile_keys.hscene").string();
    fs::copy_file(dir / scene_.toStdString(), file);
    const QString name = QString::fromStdString(fs::path(file).filename().string());
    for (const QStringList& args : {QStringList{"key", "Camera", "camera.fov_deg", "120f", "40", name},
                                    QStringList{"key", "Camera", "transform.scale", "30f", "2,2,2", name}}) {
      const test::CliRun r = test::runCli(args, tmp_.path());
      QVERIFY2(r.code == 0, qPrintable(r.err));
    }
    Json json = Json::parse(test::readDescription(file));
    int changed = 0;
    for (Json& binding : json["sequence"]["bindings"])
      for (Json& track : binding["tracks"]) {
        if (track["property"] == "camera.fov_deg") track["keys"][0]["v"] = 0.0, ++changed;
        if (track["property"] == "transform.scale") track["keys"][0]["v"] = Json::array({0.0, 3.0, 1e308}), ++changed;
      }
    QCOMPARE(changed, 2);
    test::writeDescription(file, writeJson(json));
    std::string error;
    LoadReport report;
    std::optional<SceneState> s = loadScene(file, error, nullptr, &report);
    QVERIFY2(s, error.c_str());
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    QCOMPARE(report.warnings.size(), size_t(2));
    QVERIFY2(all.find(file + ": entity 2 'Camera': camera.fov_deg key at frame 120: 0 must be from 1 to 170 °; now 1") !=
                 std::string::npos,
             all.c_str());
    QVERIFY2(all.find(file + ": entity 2 'Camera': transform.scale key at frame 30: 0,3,1e+308 must be non-zero on every axis; now 1e-09,3,1e+308") != std::string::npos,
             all.c_str());
    double fov = 0.0;
    glm::dvec3 scale(0.0);
    for (const auto& b : s->sequence.bindings)
      for (const auto& t : b.tracks) {
        if (const auto* st = std::get_if<sequencer::ScalarTrack>(&t); st && st->property == "camera.fov_deg")
          fov = st->keys.at(0).value;
        if (const auto* vt = std::get_if<sequencer::VectorTrack>(&t); vt && vt->property == "transform.scale")
          scale = vt->keys.at(0).value;
      }
    QCOMPARE(fov, 1.0);
    // What the scale field's setter makes of it: no zero axis, nothing past its range.
    const EntityField* f = findEntityField("transform.scale");
    QVERIFY(fieldValueProblem(*f, FieldValue(scale), static_cast<const Entity*>(nullptr)).empty());
    QCOMPARE(scale.y, 3.0);
  }
};

QTEST_GUILESS_MAIN(TestSceneValues)
#include "test_scene_values.moc"
