// Lights, exposure and fog from the command line, through the real program
// (tests/common/cli_runner.h): `light add` of each type with its fields,
// refused values that leave the file as it was, the new fields through `set`
// and `key`, and a render with a spot light and fog.
#include <QTemporaryDir>
#include <QtTest>

#include "cli_runner.h"
#include "file_bytes.h"
#include "scene/hscene_file.h"

using namespace hs;
using scene::Light;

class TestCliLights : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString scene_;

  test::CliRun cli(QStringList args) { return test::runCli(args, tmp_.path()); }
  std::optional<scene::SceneState> load() {
    std::string error;
    auto s = scene::loadScene(tmp_.filePath(scene_).toStdString(), error);
    if (!s) qWarning("%s", error.c_str());
    return s;
  }

 private slots:
  void initTestCase() { scene_ = test::newSceneWithCli("lights.hscene", tmp_.path()); }

  void addEachType() {
    test::CliRun r = cli({"light", "add", scene_, "--type", "spot", "--name", "Lantern", "--at", "0,-4,5", "--aim",
                          "0,0,1", "--intensity", "1500000", "--range", "30", "--inner", "20", "--outer", "40",
                          "--colour", "1,0.7,0.4", "--shadows"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("added spot light 'Lantern'"));
    QCOMPARE(cli({"light", "add", scene_, "--type", "point", "--at", "2,0,1.5", "--intensity", "800"}).code, 0);
    QCOMPARE(cli({"light", "add", scene_, "--type", "sun", "--name", "Low sun", "--intensity", "20000"}).code, 0);
    const auto s = load();
    QVERIFY(s);
    const scene::Entity* spot = s->find(s->findByName("Lantern"));
    QVERIFY(spot && spot->light && spot->light->type == Light::Type::Spot);
    QCOMPARE(spot->light->intensity, 1.5e6f);
    QCOMPARE(spot->light->range, 30.0f);
    QCOMPARE(spot->light->innerConeDeg, 20.0f);
    QCOMPARE(spot->light->outerConeDeg, 40.0f);
    QCOMPARE(spot->light->color, glm::vec3(1.0f, 0.7f, 0.4f));
    QVERIFY(spot->light->castsShadows);
    QCOMPARE(spot->transform.translation, glm::dvec3(0, -4, 5));
    // Aimed: local −Z points from the light to the aim.
    const glm::dvec3 dir = spot->transform.rotation * glm::dvec3(0, 0, -1);
    QVERIFY(glm::length(dir - glm::normalize(glm::dvec3(0, 4, -4))) < 1e-9);
    const scene::Entity* point = s->find(s->findByName("Point Light"));
    QVERIFY(point && point->light && point->light->type == Light::Type::Point && point->light->intensity == 800.0f);
    const scene::Entity* sun = s->find(s->findByName("Low sun"));
    QVERIFY(sun && sun->light && sun->light->type == Light::Type::Sun && sun->light->intensity == 20000.0f);
  }

  void refusedValuesLeaveTheFile() {
    const std::string file = tmp_.filePath(scene_).toStdString();
    const std::string before = test::readFile(file);
    struct Case {
      QStringList args;
      QString named;
    } cases[] = {
        {{"--type", "spot", "--inner", "50", "--outer", "40"}, "--inner 50 must not exceed --outer 40"},
        {{"--type", "point", "--intensity", "-1"}, "--intensity"},
        {{"--type", "point", "--intensity", "nan"}, "--intensity"},
        {{"--type", "spot", "--outer", "180"}, "--outer"},
        {{"--type", "spot", "--inner", "0"}, "--inner"},
        {{"--type", "torch"}, "--type"},
        {{"--type", "spot", "--at", "1,2,3", "--aim", "1,2,3"}, "--aim must differ from --at"},
    };
    for (const Case& c : cases) {
      const test::CliRun r = cli(QStringList{"light", "add", scene_} + c.args);
      QVERIFY2(r.code == 2, qPrintable(c.args.join(' ') + ": " + r.err));
      QVERIFY2(r.err.contains(c.named), qPrintable(r.err));
      QVERIFY2(test::readFile(file) == before, qPrintable("changed the file: " + c.args.join(' ')));
    }
  }

  // The new fields through `set` and `key`, as every field.
  void setAndKeyNewFields() {
    QCOMPARE(cli({"set", "Lantern", "light.outer_cone_deg", "60", scene_}).code, 0);
    QCOMPARE(cli({"set", "Lantern", "light.casts_shadows", "false", scene_}).code, 0);
    QCOMPARE(cli({"set", "settings.exposure_ev100", "14", scene_}).code, 0);
    QCOMPARE(cli({"set", "settings.fog_mode", "exponential_height", scene_}).code, 0);
    QCOMPARE(cli({"set", "settings.fog_density", "0.02", scene_}).code, 0);
    QCOMPARE(cli({"set", "settings.fog_colour", "0.5,0.6,0.7", scene_}).code, 0);
    const test::CliRun bad = cli({"set", "Lantern", "light.inner_cone_deg", "70", scene_});
    QCOMPARE(bad.code, 1);
    QVERIFY2(bad.err.contains("Inner cone must not exceed the outer cone (60 °)"), qPrintable(bad.err));
    QCOMPARE(cli({"key", "Lantern", "light.intensity", "0", "1000", scene_}).code, 0);
    QCOMPARE(cli({"key", "Lantern", "light.intensity", "2", "2000000", scene_}).code, 0);
    QCOMPARE(cli({"key", "Lantern", "light.outer_cone_deg", "2", "80", scene_}).code, 0);
    const auto s = load();
    QVERIFY(s);
    const scene::Entity* spot = s->find(s->findByName("Lantern"));
    QCOMPARE(spot->light->outerConeDeg, 60.0f);
    QVERIFY(!spot->light->castsShadows);
    QCOMPARE(s->settings.exposureEv100, 14.0f);
    QVERIFY(s->settings.fogMode == scene::FogMode::ExponentialHeight);
    QCOMPARE(s->settings.fogDensity, 0.02f);
    const sequencer::Binding* b = s->sequence.findBinding(spot->id);
    QVERIFY(b && b->tracks.size() == 2);
  }

  void rendersWithLightsAndFog() {
    const test::CliRun r = cli({"render", scene_, "--out", "lit.png", "--size", "96x54"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(QFile::exists(tmp_.filePath("lit.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliLights)
#include "test_cli_lights.moc"
