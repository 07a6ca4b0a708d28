// `hybridscape-cli material list|set|add|assign|delete` and `info` through the real program
// (tests/common/cli_runner.h), on a scene of format 3 whose materials come
// from its mesh when it is read.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>

#include "cli_runner.h"
#include "file_bytes.h"
#include "core/json.h"
#include "scene/hscene_file.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::test;

namespace {

const QString kFixture = QStringLiteral(HS_TEST_DATA_DIR "/file/format3_plain.hscene");

Json listJson(const QString& scene, const QString& dir) {
  const CliRun r = runCli({"material", "list", scene, "--json"}, dir);
  if (r.code != 0) qWarning("material list: %s", qPrintable(r.err));
  std::string error;
  const auto j = parseJson(r.out.toStdString(), error);
  return j ? *j : Json();
}

}  // namespace

class TestCliMaterial : public QObject {
  Q_OBJECT
 private slots:
  void listAndSet() {
    QTemporaryDir dir;
    const QString scene = dir.filePath("s.hscene");
    QVERIFY(QFile::copy(kFixture, scene));
    QFile::setPermissions(scene, QFile::ReadOwner | QFile::WriteOwner);

    Json j = listJson(scene, dir.path());
    QVERIFY(j.is_object());
    QCOMPARE(j.at("materials").size(), size_t(1));
    const Json& m = j.at("materials")[0];
    QCOMPARE(m.at("name").get<std::string>(), std::string("Bumpy / default"));
    QCOMPARE(m.at("asset").get<std::string>(), std::string("Bumpy"));
    // Every field, under the keys `set` takes.
    for (const char* key : {"base_color", "base_color_texture", "opacity", "normal_map", "normal_strength",
                            "height_map", "height_scale", "roughness", "metallic", "specular", "shininess",
                            "emission", "emission_strength", "alpha_cutout", "alpha_threshold", "two_sided",
                            "unlit", "model", "shading"})
      QVERIFY2(m.contains(key), key);
    QCOMPARE(m.at("model").get<std::string>(), std::string("pbr"));

    CliRun r = runCli({"material", "set", "Bumpy / default", "roughness", "0.25", scene}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = runCli({"material", "set", "Bumpy / default", "model", "blinn_phong", scene}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QCOMPARE(scene::sceneFileVersion(scene.toStdString()), scene::kSceneFormatVersion);
    j = listJson(scene, dir.path());
    QCOMPARE(j.at("materials")[0].at("roughness").get<double>(), 0.25);
    QCOMPARE(j.at("materials")[0].at("model").get<std::string>(), std::string("blinn_phong"));

    // The plain listing names the material and its fields.
    r = runCli({"material", "list", scene}, dir.path());
    QCOMPARE(r.code, 0);
    QVERIFY(r.out.contains("Bumpy / default  (mesh asset Bumpy)"));
    QVERIFY(r.out.contains("  roughness: 0.25"));
    // `info` mentions them.
    r = runCli({"info", scene}, dir.path());
    QCOMPARE(r.code, 0);
    QVERIFY2(r.out.contains("materials: 1"), qPrintable(r.out));
    QVERIFY(r.out.contains("Bumpy / default  (blinn_phong)"));
  }

  void badInputIsRefusedAndTheFileKept() {
    QTemporaryDir dir;
    const QString scene = dir.filePath("s.hscene");
    QVERIFY(QFile::copy(kFixture, scene));
    QFile::setPermissions(scene, QFile::ReadOwner | QFile::WriteOwner);
    struct Case {
      QStringList args;
      int code;
      QString message;
    };
    const QList<Case> cases = {
        {{"material", "set", "Bumpy / default", "opacity", "1.5", scene}, 1,
         "material 'Bumpy / default': opacity: '1.5' is out of range: Opacity must be from 0 to 1"},
        {{"material", "set", "Bumpy / default", "roughness", "nan", scene}, 1,
         "material 'Bumpy / default': roughness: 'nan' is not a finite number"},
        {{"material", "set", "Bumpy / default", "transmission", "-0.2", scene}, 1,
         "material 'Bumpy / default': transmission: '-0.2' is out of range: Transmission must be from 0 to 1"},
        {{"material", "set", "Bumpy / default", "model", "toon", scene}, 1,
         "material 'Bumpy / default': model: 'toon' is not one of: pbr lambert phong blinn_phong"},
        {{"material", "set", "Bumpy / default", "normal_map", "7", scene}, 1,
         "material 'Bumpy / default': normal_map: no texture 7 in this scene (0 for none)"},
        {{"material", "set", "Nope", "opacity", "0.5", scene}, 1, "no material named 'Nope'"},
        {{"material", "set", "Bumpy / default", "glossiness", "0.5", scene}, 1,
         "material 'Bumpy / default': no field 'glossiness'"},
        {{"material", "set", "Bumpy / default", "opacity", scene}, 2, "expected <material> <field> <value>"},
        {{"material", "frob", scene}, 2, "unknown subcommand 'frob'"},
    };
    for (const Case& c : cases) {
      const CliRun r = runCli(c.args, dir.path());
      QVERIFY2(r.code == c.code, qPrintable(c.args.join(' ') + ": " + QString::number(r.code) + " " + r.err));
      QVERIFY2(r.err.contains(c.message), qPrintable(r.err));
    }
    // Nothing was saved: still the format-3 file it was.
    QCOMPARE(scene::sceneFileVersion(scene.toStdString()), 3);
  }

  // A material made by the user, put on the mesh's slot, the asset's own
  // one then deletable; the slot's user is listed; refusals name the place.
  void addAssignDelete() {
    QTemporaryDir dir;
    const QString scene = dir.filePath("s.hscene");
    QVERIFY(QFile::copy(kFixture, scene));
    QFile::setPermissions(scene, QFile::ReadOwner | QFile::WriteOwner);

    CliRun r = runCli({"material", "set", "Bumpy / default", "roughness", "0.25", scene}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = runCli({"material", "add", "Glass", scene, "--like", "Bumpy / default"}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    Json j = listJson(scene, dir.path());
    QCOMPARE(j.at("materials").size(), size_t(2));
    const Json* glass = nullptr;
    for (const Json& m : j.at("materials"))
      if (m.at("name") == "Glass") glass = &m;
    QVERIFY(glass);
    QVERIFY(glass->at("asset").is_null());             // the scene's, not the mesh's
    QCOMPARE(glass->at("roughness").get<double>(), 0.25);  // copied from --like
    QVERIFY(glass->at("used_by").empty());

    // Deleting the mesh's own material is refused while its slot uses it.
    r = runCli({"material", "delete", "Bumpy / default", scene}, dir.path());
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("is used by mesh asset 'Bumpy' (slot 0)"), qPrintable(r.err));

    r = runCli({"material", "assign", "Bumpy", "0", "Glass", scene}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("slot 0 of"), qPrintable(r.out));
    j = listJson(scene, dir.path());
    for (const Json& m : j.at("materials")) {
      if (m.at("name") != "Glass") {
        QVERIFY(m.at("used_by").empty());
        continue;
      }
      QCOMPARE(m.at("used_by").size(), size_t(1));
      QCOMPARE(m.at("used_by")[0].at("asset").get<std::string>(), std::string("Bumpy"));
      QCOMPARE(m.at("used_by")[0].at("slot").get<int>(), 0);
    }
    // Assigning it again changes nothing and says so.
    r = runCli({"material", "assign", "Bumpy", "0", "Glass", scene}, dir.path());
    QCOMPARE(r.code, 0);
    QVERIFY2(r.out.contains("unchanged"), qPrintable(r.out));

    r = runCli({"material", "delete", "Bumpy / default", scene}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    j = listJson(scene, dir.path());
    QCOMPARE(j.at("materials").size(), size_t(1));
    QCOMPARE(j.at("materials")[0].at("name").get<std::string>(), std::string("Glass"));

    // The rendered mesh now draws with Glass: a render through the CLI
    // does not fail on the deleted material.
    r = runCli({"render", scene, "--out", dir.filePath("f.png"), "--size", "64x48"}, dir.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));

    const std::string before = hs::test::readFile(scene.toStdString());
    struct Case {
      QStringList args;
      int code;
      QString message;
    };
    const QList<Case> cases = {
        {{"material", "add", "Glass", scene}, 1, "new material: name: another material is named 'Glass'"},
        {{"material", "add", " ", scene}, 1, "new material: name: a material needs a name"},
        {{"material", "add", "X", scene, "--like", "Nope"}, 1, "--like: no material named 'Nope'"},
        {{"material", "assign", "Nope", "0", "Glass", scene}, 1, "no entity with a mesh and no mesh asset named 'Nope'"},
        {{"material", "assign", "Bumpy", "3", "Glass", scene}, 1, "mesh asset 'Bumpy' has no material slot 3 (slots 0 to 0)"},
        {{"material", "assign", "Bumpy", "-1", "Glass", scene}, 1, "slot: '-1' is not a slot number"},
        {{"material", "assign", "Bumpy", "0", "Nope", scene}, 1, "no material named 'Nope'"},
        {{"material", "delete", "Glass", scene}, 1, "is used by mesh asset 'Bumpy' (slot 0)"},
        {{"material", "delete", "Nope", scene}, 1, "no material named 'Nope'"},
    };
    for (const Case& c : cases) {
      const CliRun rr = runCli(c.args, dir.path());
      QVERIFY2(rr.code == c.code, qPrintable(c.args.join(' ') + ": " + QString::number(rr.code) + " " + rr.err));
      QVERIFY2(rr.err.contains(c.message), qPrintable(rr.err));
    }
    QVERIFY2(hs::test::readFile(scene.toStdString()) == before, "a refused command changed the file");
  }
};

QTEST_GUILESS_MAIN(TestCliMaterial)
#include "test_cli_material.moc"
