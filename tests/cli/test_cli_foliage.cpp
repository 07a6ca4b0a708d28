// `hybridscape-cli foliage ...` as a user runs it (the built program through
// QProcess): a plant generated as an asset with LODs, a type added, a
// scatter, a fill of a paint layer, `info --json` counting the instances
// per type, an exact move, a clear of a region, impostors baked and stored (then stale
// after a material edit), and every refusal one line on stderr naming the problem, the
// scene left as it was.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_checks.h"
#include "cli_runner.h"

using namespace hs;
using Run = hs::test::CliRun;

class TestCliFoliage : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString path(const QString& name) const { return tmp_.filePath(name); }
  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }

  void ok(const QStringList& args, Run* out = nullptr) {
    const Run r = cli(args);
    test::verifyCliOk(r, args);
    if (out) *out = r;
  }

  void expectError(const QStringList& args, int code, const QStringList& names) {
    test::verifyCliError(cli(args), args, code, names);
  }

  QJsonObject foliage(const QString& file) {
    const Run r = cli({"info", file, "--json"});
    return QJsonDocument::fromJson(r.out.toUtf8()).object()["foliage"].toObject();
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void plantTypeScatterInfoClear() {
    const QString f = test::newSceneWithCli(path("forest.hscene"), tmp_.path());
    ok({"terrain", "new", f, "--size", "200", "--resolution", "129", "--hills", "--height", "0,20"});
    Run plant;
    ok({"foliage", "plant", "Stone", "--kind", "rock", "--seed", "4", f}, &plant);
    QVERIFY2(plant.out.contains("LOD 1"), qPrintable(plant.out));
    ok({"foliage", "type", "add", "Stones", "--mesh", "Stone", "--density", "300", "--spacing", "2", f});
    Run scatter;
    ok({"foliage", "scatter", "Stones", f, "--seed", "9", "--on", "terrain"}, &scatter);
    QVERIFY2(scatter.out.contains("foliage cells written"), qPrintable(scatter.out));
    QJsonObject info = foliage(f);
    const int placed = info["instances"].toInt();
    QVERIFY2(placed > 400, qPrintable(QString::number(placed)));  // 300/ha over 4 ha, thinned by spacing
    QCOMPARE(info["types"].toArray()[0].toObject()["name"].toString(), QString("Stones"));
    QCOMPARE(info["types"].toArray()[0].toObject()["instances"].toInt(), placed);
    Run text;
    ok({"info", f}, &text);
    QVERIFY2(text.out.contains("Stones: mesh \"Stone\", " + QString::number(placed) + " instances"), qPrintable(text.out));
    // An exact move of those in the west half: every one moved, none lost.
    Run move;
    ok({"foliage", "move", "Stones", f, "--offset", "3.5,-2,0", "--region", "-100,-100,0,100"}, &move);
    const int movedCount = move.out.section(' ', 0, 0).toInt();
    QVERIFY2(movedCount > 50 && move.out.contains(" moved;"), qPrintable(move.out));
    QCOMPARE(foliage(f)["instances"].toInt(), placed);
    expectError({"foliage", "move", "Stones", f, "--offset", "1,2"}, 2, {"--offset"});
    ok({"foliage", "clear", "Stones", f, "--region", "-100,-100,0,100"});
    const int left = foliage(f)["instances"].toInt();
    QVERIFY(left > 0 && left < placed);
    ok({"foliage", "clear", "Stones", f});
    QCOMPARE(foliage(f)["instances"].toInt(), 0);
  }

  // `foliage impostors`: the far level of each type's mesh baked and stored
  // (`info` says "none", then "stored"); a second run bakes nothing; a
  // recoloured material makes it stale and --all or a plain run bakes again.
  void impostorsBakedAndStored() {
    const QString f = test::newSceneWithCli(path("impostors.hscene"), tmp_.path());
    ok({"foliage", "plant", "Stone", "--kind", "rock", "--seed", "4", f});
    ok({"foliage", "type", "add", "Stones", "--mesh", "Stone", f});
    auto impostorOf = [&](const QString& asset) {
      const Run r = cli({"info", f, "--json"});
      for (const QJsonValue a : QJsonDocument::fromJson(r.out.toUtf8()).object()["assets"].toArray())
        if (a.toObject()["name"].toString() == asset) return a.toObject()["impostor"].toString();
      return QString("no such asset");
    };
    QCOMPARE(impostorOf("Stone"), QString("none"));
    Run bake;
    ok({"foliage", "impostors", f}, &bake);
    QVERIFY2(bake.out.contains("impostor of \"Stone\": 12 x 12 frames of 64 px") &&
                 bake.out.contains("1 impostor(s) stored"),
             qPrintable(bake.out));
    QCOMPARE(impostorOf("Stone"), QString("stored"));
    Run text;
    ok({"info", f}, &text);
    QVERIFY2(text.out.contains("impostor: stored"), qPrintable(text.out));
    Run again;
    ok({"foliage", "impostors", f}, &again);
    QVERIFY2(again.out.contains("nothing baked"), qPrintable(again.out));
    ok({"material", "set", "Stone / rock", "base_color", "0.2,0.2,0.2", f});
    QCOMPARE(impostorOf("Stone"), QString("stale"));
    ok({"foliage", "impostors", f, "--all"}, &bake);
    QVERIFY2(bake.out.contains("1 impostor(s) stored"), qPrintable(bake.out));
    QCOMPARE(impostorOf("Stone"), QString("stored"));
  }

  // `foliage fill`: a type painted where a terrain paint layer weighs
  // enough (the paint rules put grass on the gentle ground below 31 m), no
  // more than a scatter over everything; refusals name the layer or option.
  void fillAPaintLayer() {
    const QString f = test::newSceneWithCli(path("layer.hscene"), tmp_.path());
    ok({"terrain", "new", f, "--size", "200", "--resolution", "129", "--hills", "--height", "0,60"});
    ok({"terrain", "paint-rules", f});
    ok({"foliage", "plant", "Stone", "--kind", "rock", f});
    ok({"foliage", "type", "add", "Stones", "--mesh", "Stone", "--density", "300", "--spacing", "2", f});
    Run fill;
    ok({"foliage", "fill", "Stones", f, "--layer", "Grass", "--min-weight", "0.5", "--seed", "3"}, &fill);
    QVERIFY2(fill.out.contains("placed"), qPrintable(fill.out));
    const int inLayer = foliage(f)["instances"].toInt();
    ok({"foliage", "clear", "Stones", f});
    ok({"foliage", "scatter", "Stones", f, "--seed", "3", "--on", "terrain"});
    const int everywhere = foliage(f)["instances"].toInt();
    qInfo("grass layer: %d of %d", inLayer, everywhere);
    QVERIFY2(inLayer > 20 && inLayer < everywhere * 9 / 10, qPrintable(QString("%1 of %2").arg(inLayer).arg(everywhere)));
    expectError({"foliage", "fill", "Stones", f, "--layer", "Nope"}, 1, {"paint layer", "Nope"});
    expectError({"foliage", "fill", "Stones", f, "--layer", "Grass", "--min-weight", "2"}, 2, {"--min-weight"});
    expectError({"foliage", "fill", "Stones", f}, 2, {"--layer"});
    QCOMPARE(foliage(f)["instances"].toInt(), everywhere);  // the refusals changed nothing
  }

  void refusalsNameTheProblemAndChangeNothing() {
    const QString f = test::newSceneWithCli(path("bad.hscene"), tmp_.path());
    ok({"foliage", "plant", "Stone", "--kind", "rock", f});
    const QByteArray before = [&] {
      QFile file(f);
      file.open(QIODevice::ReadOnly);
      return file.readAll();
    }();
    expectError({"foliage", "type", "add", "T", "--mesh", "Nope", f}, 1, {"Nope"});
    expectError({"foliage", "type", "add", "T", "--mesh", "Stone", "--density", "-1", f}, 2, {"--density"});
    expectError({"foliage", "type", "add", "T", "--mesh", "Stone", "--density", "1e9", f}, 2, {"--density"});
    expectError({"foliage", "scatter", "Ghost", f}, 1, {"Ghost"});
    expectError({"foliage", "plant", "Stone", "--kind", "rock", f}, 1, {"Stone", "exists"});
    expectError({"foliage", "plant", "X", "--kind", "palm", f}, 2, {"--kind"});
    expectError({"foliage", "prune", f}, 2, {"unknown subcommand", "prune"});
    // Nothing scattered on a scene with no ground.
    ok({"foliage", "type", "add", "T", "--mesh", "Stone", f});
    expectError({"foliage", "scatter", "T", f}, 1, {"nothing to scatter on"});
    QFile file(f);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QVERIFY(file.readAll() != before);  // the type add above was saved ...
    QCOMPARE(foliage(f)["instances"].toInt(), 0);  // ... and nothing else
  }
};

QTEST_GUILESS_MAIN(TestCliFoliage)
#include "test_cli_foliage.moc"
