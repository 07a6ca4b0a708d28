// `hybridscape-cli terrain ...` as a user runs it (the built program through
// QProcess): new, import (DEM), erode, paint-rules, export, and the
// terrains in `info`. Results are checked through the files written; every
// error exits non-zero with one line on stderr that names the problem.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <OpenImageIO/imageio.h>

#include "cli_runner.h"
#include "scene/hscene_file.h"

using namespace hs;
using hs::test::kCli;

namespace {

const QString kDem = HS_TEST_DATA_DIR "/terrain/dem_wgs84.tif";

using Run = hs::test::CliRun;

}  // namespace

class TestCliTerrain : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString path(const QString& name) const { return tmp_.filePath(name); }

  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }

  void ok(const QStringList& args, Run* out = nullptr) {
    const Run r = cli(args);
    QVERIFY2(r.code == 0, qPrintable("hybridscape-cli " + args.join(' ') + ": " + r.err));
    if (out) *out = r;
  }

  // Non-zero exit `code` and one line on stderr (warnings aside) naming each of `names`.
  void expectError(const QStringList& args, int code, const QStringList& names) {
    const Run r = cli(args);
    const QString cmd = "hybridscape-cli " + args.join(' ');
    QVERIFY2(r.code == code, qPrintable(QString("%1: exit %2, expected %3; stderr: %4").arg(cmd).arg(r.code).arg(code).arg(r.err)));
    QStringList lines = r.err.split('\n', Qt::SkipEmptyParts);
    lines.removeIf([](const QString& l) { return l.startsWith("warning:"); });
    QVERIFY2(lines.size() == 1, qPrintable(QString("%1: expected one line on stderr, got:\n%2").arg(cmd, r.err)));
    for (const QString& n : names)
      QVERIFY2(lines[0].contains(n), qPrintable(QString("%1: '%2' not in: %3").arg(cmd, n, lines[0])));
  }

  QJsonArray terrains(const QString& file) {
    const Run r = cli({"info", file, "--json"});
    return QJsonDocument::fromJson(r.out.toUtf8()).object()["terrains"].toArray();
  }

  QString newScene(const QString& name) { return test::newSceneWithCli(path(name), tmp_.path()); }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
  }

  void helpForEachSubcommand() {
    for (const char* sub : {"new", "import", "erode", "paint-rules", "export", "layer"}) {
      Run r;
      ok({"terrain", sub, "--help"}, &r);
      QVERIFY2(r.out.startsWith("usage: hybridscape-cli terrain"), qPrintable(r.out));
    }
    Run r;
    ok({"terrain", "--help"}, &r);
    QVERIFY(r.out.contains("paint-rules"));
    expectError({"terrain", "flatten"}, 2, {"unknown subcommand", "flatten"});
  }

  void newMakesATerrainOfTheGivenSize() {
    const QString f = newScene("new.hscene");
    Run r;
    ok({"terrain", "new", f, "--size", "500x300", "--resolution", "257x129", "--name", "Valley", "--height", "10,90",
        "--hills"},
       &r);
    QVERIFY(r.out.contains("500.000 x 300.000 m"));
    QVERIFY(r.out.contains("tiles written"));
    const QJsonArray t = terrains(f);
    QCOMPARE(t.size(), 1);
    const QJsonObject v = t[0].toObject();
    QCOMPARE(v["name"].toString(), QString("Valley"));
    QCOMPARE(v["size_m"].toArray()[0].toDouble(), 500.0);
    QCOMPARE(v["size_m"].toArray()[1].toDouble(), 300.0);
    QCOMPARE(v["samples"].toArray()[0].toInt(), 257);
    QCOMPARE(v["samples"].toArray()[1].toInt(), 129);
    QVERIFY(v["height_range_m"].toArray()[0].toDouble() >= 10.0 - 1e-3);
    QVERIFY(v["height_range_m"].toArray()[1].toDouble() <= 90.0 + 1e-3);
    QCOMPARE(v["layers"].toArray().size(), 8);
    // The text form says the size in metres too.
    Run info;
    ok({"info", f}, &info);
    QVERIFY2(info.out.contains("Valley: 500.000 x 300.000 m, 257 x 129 samples"), qPrintable(info.out));
    QVERIFY(info.out.contains("terrains: 1"));

    expectError({"terrain", "new", f, "--resolution", "257"}, 2, {"--size"});
    expectError({"terrain", "new", f, "--size", "100", "--resolution", "9000"}, 2, {"9000", "2 to 8193"});
    expectError({"terrain", "new", f, "--size", "-5x10", "--resolution", "65"}, 2, {"-5x10"});
    expectError({"terrain", "new", f, "--size", "100", "--resolution", "65", "--height", "9,1"}, 2, {"--height"});
    expectError({"terrain", "new", f, "--size", "100", "--resolution", "65", "--name", "Valley"}, 1, {"already", "Valley"});
    expectError({"terrain", "new", path("missing.hscene"), "--size", "100", "--resolution", "65"}, 1,
                {"missing.hscene", "hybridscape-cli new"});
    expectError({"terrain", "new", f, "--size", "100", "--resolution", "65", "--bogus"}, 2, {"--bogus"});
  }

  void importKeepsTrueGroundSizeAndCrs() {
    const QString f = newScene("dem.hscene");
    Run r;
    ok({"terrain", "import", kDem, f, "--resolution", "129"}, &r);
    QVERIFY2(r.out.contains("129x129 samples"), qPrintable(r.out));
    const QJsonObject t = terrains(f)[0].toObject();
    QCOMPARE(t["name"].toString(), QString("dem_wgs84"));
    QVERIFY(t["crs"].toObject()["georeferenced"].toBool());
    // The DEM's geodesic extent is 28608 x 33085 m (docs/terrain.md); resampling keeps it.
    QVERIFY(std::abs(t["size_m"].toArray()[0].toDouble() / 28608.0 - 1.0) < 0.01);
    QVERIFY(std::abs(t["size_m"].toArray()[1].toDouble() / 33085.0 - 1.0) < 0.01);
    // A window, in degrees, as a second terrain; UTM on request.
    ok({"terrain", "import", kDem, f, "--window", "lonlat:-97.45,32.68,-97.35,32.75", "--crs", "utm", "--name", "Part"}, &r);
    const QJsonArray both = terrains(f);
    QCOMPARE(both.size(), 2);
    QVERIFY(both[1].toObject()["crs"].toObject()["name"].toString().contains("UTM"));
    QVERIFY(both[1].toObject()["size_m"].toArray()[0].toDouble() < 10000.0);
    // Into an existing terrain: its grid is kept, the heights replaced (one undo step).
    ok({"terrain", "import", kDem, f, "--into", "Part"}, &r);
    QVERIFY(r.out.contains("resampled onto the terrain"));
    QCOMPARE(terrains(f).size(), 2);

    expectError({"terrain", "import", path("nope.tif"), f}, 1, {"nope.tif"});
    expectError({"terrain", "import", HS_TEST_DATA_DIR "/terrain/ATTRIBUTION.md", f}, 1, {"ATTRIBUTION.md"});
    expectError({"terrain", "import", kDem, f, "--window", "lonlat:1,2,3"}, 2, {"--window"});
    expectError({"terrain", "import", kDem, f, "--window", "lonlat:0,0,1,1"}, 1, {"dem_wgs84.tif"});
    expectError({"terrain", "import", kDem, f, "--crs", "EPSG:999999"}, 1, {"dem_wgs84.tif"});
    expectError({"terrain", "import", kDem, f, "--into", "Nothing"}, 1, {"no terrain named 'Nothing'"});
    expectError({"terrain", "import", kDem, f, "--resampling", "lanczos"}, 2, {"--resampling"});
    expectError({"terrain", "import", kDem}, 2, {"expected"});
  }

  void erodePrintsMassErrorAndTime() {
    const QString f = newScene("erode.hscene");
    ok({"terrain", "new", f, "--size", "256", "--resolution", "257", "--hills", "--height", "0,80", "--name", "A"});
    Run r;
    ok({"terrain", "erode", f, "--thermal", "--iterations", "30", "--talus", "20"}, &r);
    QVERIFY2(r.out.contains("mass error") && r.out.contains("relative"), qPrintable(r.out));
    QVERIFY(r.out.contains("time ") && r.out.contains(" s ("));
    ok({"terrain", "erode", f, "--hydraulic", "--iterations", "40", "--rain", "0.05"}, &r);
    QVERIFY(r.out.contains("mass error"));
    // Out-of-range values are refused by the declaration (the solvers
    // still clamp what calls hand them, test_terrain_erosion).
    expectError({"terrain", "erode", f, "--thermal", "--iterations", "2", "--talus", "400"}, 2,
                {"--talus", "400", "0 to 90 degrees"});
    ok({"terrain", "new", f, "--size", "64", "--resolution", "65", "--name", "B"});
    expectError({"terrain", "erode", f, "--thermal"}, 1, {"2 terrains", "--terrain", "'A'", "'B'"});
    expectError({"terrain", "erode", f, "--terrain", "Z", "--thermal"}, 1, {"no terrain named 'Z'"});
    expectError({"terrain", "erode", f, "--terrain", "A"}, 2, {"--thermal or --hydraulic"});
    expectError({"terrain", "erode", f, "--terrain", "A", "--thermal", "--hydraulic"}, 2, {"--thermal or --hydraulic"});
    expectError({"terrain", "erode", f, "--terrain", "A", "--thermal", "--iterations", "x"}, 2, {"--iterations"});
    expectError({"terrain", "erode", f, "--terrain", "A", "--thermal", "--mask-layer", "12"}, 2, {"--mask-layer"});
    const QString empty = newScene("empty.hscene");
    expectError({"terrain", "erode", empty, "--thermal"}, 1, {"no terrain", "terrain new"});
  }

  void paintRulesPaintAndSave() {
    const QString f = newScene("paint.hscene");
    ok({"terrain", "new", f, "--size", "256", "--resolution", "257", "--hills", "--height", "0,120"});
    Run r;
    ok({"terrain", "paint-rules", f, "--show"}, &r);
    QVERIFY(r.out.contains("Sandstone"));
    ok({"terrain", "paint-rules", f}, &r);
    QVERIFY2(r.out.contains("paint rules: 4 rules"), qPrintable(r.out));
    std::string error;
    auto s = scene::loadScene(f.toStdString(), error);
    QVERIFY2(s, error.c_str());
    const auto& paint = s->terrains.begin()->second.data->terrain().paint;
    QVERIFY(paint.grid(1).allocatedTiles() > 0);  // grass on the gentle ground
    // Rules from a file become the terrain's; a bad one is refused, naming the file.
    QFile rules(path("rules.json"));
    QVERIFY(rules.open(QIODevice::WriteOnly));
    rules.write(R"([{"layer": 7, "strength": 1, "use_altitude": true, "altitude_min": 60, "altitude_max": 200,
                     "altitude_blend": 5, "use_slope": false, "slope_min": 0, "slope_max": 90, "slope_blend": 1}])");
    rules.close();
    ok({"terrain", "paint-rules", f, "--rules", path("rules.json")}, &r);
    QVERIFY(r.out.contains("1. layer 7 (Snow)"));
    QFile bad(path("bad.json"));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write(R"([{"layer": 40, "strength": 1}])");
    bad.close();
    expectError({"terrain", "paint-rules", f, "--rules", path("bad.json")}, 1, {"bad.json", "layer"});
    expectError({"terrain", "paint-rules", f, "--rules", path("none.json")}, 1, {"none.json"});
    expectError({"terrain", "paint-rules", f, "--rules", path("rules.json"), "--defaults"}, 2, {"--defaults"});
  }

  // A layer's material as the Layers editor sets it: values and a normal
  // map kept (by absolute path) in the saved file; an unreadable image, a
  // layer the terrain lacks and a value out of range refused, naming them,
  // with the file unchanged.
  void layerSetsAMaterial() {
    const QString f = newScene("layer.hscene");
    ok({"terrain", "new", f, "--size", "64", "--resolution", "65"});
    {  // a flat tangent-space normal map, 4 x 4
      const std::vector<uint8_t> rgb = [] {
        std::vector<uint8_t> v;
        for (int i = 0; i < 16; ++i) v.insert(v.end(), {128, 128, 255});
        return v;
      }();
      const std::string file = path("flat_normal.png").toStdString();
      auto out = OIIO::ImageOutput::create(file);
      QVERIFY(out && out->open(file, OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::UINT8)) &&
              out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) && out->close());
    }
    Run r;
    ok({"terrain", "layer", f, "--layer", "1", "--name", "Moss", "--albedo", "0.1,0.4,0.1", "--roughness", "0.6",
        "--tiling", "2.5", "--normal-map", "flat_normal.png"},
       &r);
    QVERIFY2(r.out.contains("1. Moss"), qPrintable(r.out));
    std::string error;
    auto s = scene::loadScene(f.toStdString(), error);
    QVERIFY2(s, error.c_str());
    const terrain::Material& m = s->terrains.begin()->second.materials[1];
    QCOMPARE(m.name, std::string("Moss"));
    QCOMPARE(m.albedo, glm::vec3(0.1f, 0.4f, 0.1f));
    QCOMPARE(m.roughness, 0.6f);
    QCOMPARE(m.tilingMetres, 2.5f);
    QCOMPARE(QString::fromStdString(m.normalTexture), QFileInfo(path("flat_normal.png")).absoluteFilePath());
    const QByteArray before = [&] {
      QFile file(f);
      return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
    }();
    QFile junk(path("junk.png"));
    QVERIFY(junk.open(QIODevice::WriteOnly));
    junk.write("not an image");
    junk.close();
    expectError({"terrain", "layer", f, "--layer", "1", "--normal-map", path("junk.png")}, 1, {"--normal-map", "junk.png"});
    expectError({"terrain", "layer", f, "--layer", "9", "--roughness", "0.5"}, 1, {"8 layers", "9"});
    expectError({"terrain", "layer", f, "--layer", "1", "--roughness", "2"}, 2, {"--roughness"});
    expectError({"terrain", "layer", f, "--roughness", "0.5"}, 2, {"--layer"});
    QFile after(f);
    QVERIFY(after.open(QIODevice::ReadOnly));
    QVERIFY2(after.readAll() == before, "a refused change must leave the file as it was");
    // "none" removes the map again.
    ok({"terrain", "layer", f, "--layer", "1", "--normal-map", "none"});
    s = scene::loadScene(f.toStdString(), error);
    QVERIFY2(s, error.c_str());
    QVERIFY(s->terrains.begin()->second.materials[1].normalTexture.empty());
  }

  void exportEveryFormat() {
    const QString f = newScene("export.hscene");
    ok({"terrain", "new", f, "--size", "200x100", "--resolution", "201x101", "--hills", "--height", "5,50"});
    for (const char* ext : {"png", "exr", "tif", "r16"}) {
      const QString out = path(QString("h.%1").arg(ext));
      Run r;
      ok({"terrain", "export", f, "--out", out}, &r);
      QVERIFY(QFileInfo::exists(out));
      if (QString(ext) != "r16") {
        auto in = OIIO::ImageInput::open(out.toStdString());
        QVERIFY(in);
        QCOMPARE(in->spec().width, 201);
        QCOMPARE(in->spec().height, 101);
      } else {
        QCOMPARE(QFileInfo(out).size(), qint64(201 * 101 * 2));
        QVERIFY(QFileInfo::exists(out + ".json"));
      }
    }
    Run r;
    ok({"terrain", "export", f, "--weights", path("w")}, &r);
    QCOMPARE(QDir(path("w")).entryList(QDir::Files).size(), 8);
    expectError({"terrain", "export", f, "--out", path("h.bmp")}, 1, {"h.bmp", ".r16"});
    expectError({"terrain", "export", f}, 2, {"--out"});
    expectError({"terrain", "export", f, "--out", path("h.png"), "--range", "5,1"}, 2, {"--range"});
    expectError({"terrain", "export", path("no.hscene"), "--out", path("h.png")}, 1, {"no.hscene"});
  }

  // Without the GDAL module (terrain/gdal_door.h) a DEM import and a
  // GeoTIFF export fail saying which module is missing and where it was
  // looked for, the scene file stays as it was, and the rest works: a new
  // terrain, an export to PNG.
  void withoutTheGdalModuleDemsFailAndNothingElse() {
    const QString f = newScene("no_gdal.hscene");
    const QString missing = "/nonexistent/hybridscape-gdal.so";
    qputenv("HS_GDAL_MODULE", missing.toUtf8());
    const QByteArray before = [&] {
      QFile in(f);
      return in.open(QIODevice::ReadOnly) ? in.readAll() : QByteArray();
    }();
    const Run import = cli({"terrain", "import", kDem, f});
    QFile again(f);
    QVERIFY(again.open(QIODevice::ReadOnly));
    const bool unchanged = again.readAll() == before;
    const Run made = cli({"terrain", "new", f, "--size", "100", "--resolution", "65", "--hills"});
    const Run tif = cli({"terrain", "export", f, "--out", path("no_gdal.tif")});
    const Run png = cli({"terrain", "export", f, "--out", path("no_gdal.png")});
    qunsetenv("HS_GDAL_MODULE");
    QCOMPARE(import.code, 1);
    for (const QString& err : {import.err, tif.err}) {
      QVERIFY2(err.contains("the GDAL module hybridscape-gdal.so (GDAL and PROJ) is missing") &&
                   err.contains(missing + " (not there)") && err.contains("HS_GDAL_MODULE names it"),
               qPrintable(err));
    }
    QVERIFY2(import.err.contains("dem_wgs84.tif"), qPrintable(import.err));
    QVERIFY(!before.isEmpty() && unchanged);
    QVERIFY2(made.code == 0, qPrintable(made.err));
    QCOMPARE(tif.code, 1);
    QVERIFY2(tif.err.contains("no_gdal.tif"), qPrintable(tif.err));
    QVERIFY(!QFileInfo::exists(path("no_gdal.tif")));
    QVERIFY2(png.code == 0 && QFileInfo::exists(path("no_gdal.png")), qPrintable(png.err));
  }
};

QTEST_GUILESS_MAIN(TestCliTerrain)
#include "test_cli_terrain.moc"
