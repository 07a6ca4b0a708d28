// `hybridscape-cli particles add`, `set EMITTER particles.FIELD` and the
// emitters in `info --time` as a user runs them (the built program through
// QProcess): presets placed where asked, live counts at a time against the
// emitter's own numbers (a point emitter's rate times its lifetime), fields
// and keyed lists set and read back, and every refusal one line on stderr
// naming the emitter and the field, the file unchanged.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_checks.h"
#include "cli_runner.h"
#include "file_bytes.h"

using namespace hs;
using Run = hs::test::CliRun;

class TestCliParticles : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString path(const QString& name) const { return tmp_.filePath(name); }
  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }
  Run ok(const QStringList& args) {
    const Run r = cli(args);
    test::verifyCliOk(r, args);
    return r;
  }

  QJsonObject particles(const QString& file, const QString& time = "0") {
    const Run r = cli({"info", file, "--json", "--time", time});
    return QJsonDocument::fromJson(r.out.toUtf8()).object()["particles"].toObject();
  }
  static QJsonObject emitterNamed(const QJsonObject& particles, const QString& name) {
    for (const QJsonValue& v : particles["emitters"].toArray())
      if (v.toObject()["name"].toString() == name) return v.toObject();
    return {};
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void addSetAndCount() {
    const QString f = test::newSceneWithCli(path("valley.hscene"), tmp_.path());
    Run add = ok({"particles", "add", "torch", f, "--name", "Gate torch", "--at", "500120,4400310,412", "--seed", "3"});
    QVERIFY2(add.out.contains("emitter \"Gate torch flame\"") && add.out.contains("emitter \"Gate torch smoke\""),
             qPrintable(add.out));
    QVERIFY2(add.out.contains("500120.000, 4400310.000, 412.000"), qPrintable(add.out));
    ok({"particles", "add", "snow", f, "--area", "-50,-50,50,50", "--rate", "1000"});

    // A steady emitter's live count is its rate times its lifetime: snow
    // at 1000 per second living 30..40 s has about 35,000 in the air (the
    // preset starts 60 s before the shot, so it is steady at t = 0).
    QJsonObject snow = emitterNamed(particles(f), "Snow");
    QVERIFY(!snow.isEmpty());
    const double live = snow["live"].toDouble();
    QVERIFY2(std::abs(live - 35000.0) < 0.02 * 35000.0, qPrintable(QString::number(live)));
    QCOMPARE(snow["emitter"].toObject()["rate_per_s"].toDouble(), 1000.0);

    // Fields through `set`, read back from the file; an unchanged value says so.
    Run set = ok({"set", "Snow", "particles.rate_per_s", "200", f});
    QVERIFY2(set.out.contains("set particles.rate_per_s"), qPrintable(set.out));
    ok({"set", "Snow", "particles.lifetime_s", "10,10", f});
    ok({"set", "Snow", "particles.start_s", "0", f});
    snow = emitterNamed(particles(f, "5"), "Snow");
    QCOMPARE(snow["live"].toDouble(), 1000.0);  // 200 per second for the 5 s since it started
    // --time takes frames too (60 fps: 300f = 5 s).
    QCOMPARE(emitterNamed(particles(f, "300f"), "Snow")["live"].toDouble(), 1000.0);
    Run same = ok({"set", "Snow", "particles.rate_per_s", "200", f});
    QVERIFY2(same.out.contains("unchanged"), qPrintable(same.out));
    // A keyed rate: 0 at 0 s rising to 400 at 10 s; by 10 s, 2,000 born (the
    // exact integral), all alive with a 10 s life.
    ok({"set", "Snow", "particles.rate_keys", "[[0, 0], [10, 400]]", f});
    QCOMPARE(emitterNamed(particles(f, "10"), "Snow")["live"].toDouble(), 2000.0);
    ok({"set", "Snow", "particles.collision", "bounce", f});
    QCOMPARE(emitterNamed(particles(f), "Snow")["emitter"].toObject()["collision"].toString(), QString("bounce"));

    // The text listing.
    const Run text = ok({"info", f, "--time", "10"});
    QVERIFY2(text.out.contains("Snow: snowflake alpha, 2000 particles live"), qPrintable(text.out));
    QVERIFY2(text.out.contains("Gate torch flame: flame additive"), qPrintable(text.out));
  }

  // Spawn values keyed on the timeline through `key` (the same edit as the
  // editor's key button); fields that are not spawn values are refused.
  void spawnValuesKeyedOnTheTimeline() {
    const QString f = test::newSceneWithCli(path("keyed.hscene"), tmp_.path());
    ok({"particles", "add", "dust", f, "--name", "Puff"});
    ok({"key", "Puff", "particles.size_m", "0", "0.1", f});
    const Run second = ok({"key", "Puff", "particles.size_m", "10", "2.1", f});
    QVERIFY2(second.out.contains("particles.size_m") && second.out.contains("2 key(s)"), qPrintable(second.out));
    ok({"key", "Puff", "particles.direction", "5", "1,0,0", f});
    const std::string before = test::readFile(f.toStdString());
    const QStringList notSpawn = {"key", "Puff", "particles.drag_per_s", "0", "1", f};
    test::verifyCliError(cli(notSpawn), notSpawn, 1, {"particles.drag_per_s", "spawn values"});
    const QStringList outOfRange = {"key", "Puff", "particles.size_m", "0", "-2", f};
    test::verifyCliError(cli(outOfRange), outOfRange, 1, {"particles.size_m"});
    const QStringList noEmitter = {"key", "Camera", "particles.size_m", "0", "1", f};
    test::verifyCliError(cli(noEmitter), noEmitter, 1, {"Camera", "particles"});
    QVERIFY2(test::readFile(f.toStdString()) == before, "a refused key changed the file");

    // The rate and the wind go into the emitter's own lists: a key at 2 s
    // and one at 6 s (frame 360 at 60 fps), then 2 s again replaced.
    ok({"set", "Puff", "particles.lifetime_s", "100,100", f});
    ok({"set", "Puff", "particles.start_s", "0", f});
    ok({"key", "Puff", "particles.rate_per_s", "2", "10", f});
    ok({"key", "Puff", "particles.rate_per_s", "360f", "50", f});
    const Run rate = ok({"key", "Puff", "particles.rate_per_s", "2", "30", f});
    QVERIFY2(rate.out.contains("rate_keys has 2 key(s)"), qPrintable(rate.out));
    const QJsonObject puff = emitterNamed(particles(f, "6"), "Puff")["emitter"].toObject();
    QCOMPARE(puff["rate_keys"].toArray().size(), 2);
    QCOMPARE(puff["rate_keys"].toArray()[0].toArray()[1].toDouble(), 30.0);
    // Born by 6 s: 30 per second held from 0 to 2, then the ramp to 50 (the exact integral).
    QCOMPARE(emitterNamed(particles(f, "6"), "Puff")["live"].toDouble(), 2 * 30.0 + 4 * 40.0);
    ok({"key", "Puff", "particles.wind_m_per_s", "3", "4,0,0", f});
    QCOMPARE(emitterNamed(particles(f), "Puff")["emitter"].toObject()["wind_keys"].toArray().size(), 1);
    const std::string keyed = test::readFile(f.toStdString());
    const QStringList badRate = {"key", "Puff", "particles.rate_per_s", "4", "-3", f};
    test::verifyCliError(cli(badRate), badRate, 1, {"Puff", "rate_per_s"});
    const QStringList badWind = {"key", "Puff", "particles.wind_m_per_s", "4", "1,2", f};
    test::verifyCliError(cli(badWind), badWind, 1, {"Puff", "wind_m_per_s"});
    const QStringList withInterp = {"key", "Puff", "particles.rate_per_s", "4", "3", f, "--interp", "cubic"};
    test::verifyCliError(cli(withInterp), withInterp, 2, {"--interp", "linear"});
    QVERIFY2(test::readFile(f.toStdString()) == keyed, "a refused key changed the file");

    // A draw_mesh naming no mesh entity: `info` names emitter and field.
    ok({"set", "Puff", "particles.draw_mesh", "Pebble", f});
    const Run info = ok({"info", f, "--time", "1"});
    QVERIFY2(info.out.contains("Puff: problem: emitter 'Puff', field 'draw_mesh': no entity 'Pebble' with a mesh"),
             qPrintable(info.out));
    QVERIFY2(emitterNamed(particles(f, "1"), "Puff")["error"].toString().contains("draw_mesh"), "no error in --json");
  }

  void refusalsNameEmitterAndFieldAndChangeNothing() {
    const QString f = test::newSceneWithCli(path("refuse.hscene"), tmp_.path());
    ok({"particles", "add", "dust", f, "--name", "Road dust"});
    const std::string before = test::readFile(f.toStdString());
    test::verifyCliError(cli({"particles", "add", "rain", f}), {"particles add rain"}, 1, {"rain", "snow", "campfire"});
    test::verifyCliError(cli({"particles", "add", "snow", f, "--rate", "-1"}), {"--rate -1"}, 2, {"--rate"});
    test::verifyCliError(cli({"particles", "add", "snow", f, "--rate", "1e8"}), {"--rate 1e8"}, 2, {"--rate"});
    test::verifyCliError(cli({"particles", "add", "snow", f, "--at", "nan,0,0"}), {"--at nan"}, 2, {"--at"});
    const QStringList bad[][2] = {
        {{"particles.drag_per_s", "nan"}, {"drag_per_s"}},
        {{"particles.drag_per_s", "-3"}, {"drag_per_s"}},
        {{"particles.rate_per_s", "-1"}, {"rate_per_s"}},
        {{"particles.lifetime_s", "5,1"}, {"lifetime_s", "Road dust"}},
        {{"particles.size_m", "inf,1"}, {"size_m"}},
        {{"particles.rate_keys", "[[1, 10], [1, 20]]"}, {"rate_keys", "Road dust", "coincides"}},
        {{"particles.rate_keys", "[[1, 10"}, {"rate_keys", "JSON"}},
        {{"particles.shape", "blob"}, {"shape", "blob"}},
        {{"particles.nope", "1"}, {"nope"}},
    };
    for (const auto& c : bad) {
      const QStringList args = QStringList{"set", "Road dust"} + c[0] + QStringList{f};
      test::verifyCliError(cli(args), args, 1, c[1]);
    }
    const QStringList noComponent = {"set", "Camera", "particles.rate_per_s", "5", f};
    test::verifyCliError(cli(noComponent), noComponent, 1, {"Camera", "particles"});
    QVERIFY2(test::readFile(f.toStdString()) == before, "a refused command changed the file");
  }
};

QTEST_GUILESS_MAIN(TestCliParticles)
#include "test_cli_particles.moc"
