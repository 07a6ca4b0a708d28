// `hybridscape-cli key --material` / `--settings` as a user runs them (the
// built program through QProcess, the real renderer): keys on a material's
// colour and the scene's exposure, the frames `render --frames` writes at
// the keys against scenes where those values are set without animation
// (the same pixels), `sequence` and `info --json` listing the tracks, and
// every refusal with its message.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <vector>

#include "cli_runner.h"
#include "file_pixels.h"
#include "file_bytes.h"
#include "scene/scene_state.h"

using namespace hs;
using hs::test::kCli;
using Run = hs::test::CliRun;
namespace fs = std::filesystem;

namespace {

// A 6 m box at the origin, in front of the starter scene's camera.
const char* kBox =
    "v -3 -3 -3\nv 3 -3 -3\nv 3 3 -3\nv -3 3 -3\nv -3 -3 3\nv 3 -3 3\nv 3 3 3\nv -3 3 3\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

const QString kMaterial = "box / default";
// The starter scene's exposure (the reference EV100, 15.2 − log2 π), as
// text that reads back to the same float.
const QString kDefaultExposure = QString::number(double(scene::SceneSettings{}.exposureEv100), 'g', 9);

std::vector<unsigned char> pixels(const QString& path) { return hs::test::filePixels(path.toStdString()); }

}  // namespace

class TestCliObjectTracks : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;

  Run cli(const QStringList& args) { return hs::test::runCli(args, tmp_.path()); }
  QString path(const QString& name) const { return tmp_.filePath(name); }

  // The frame `frame` of `scene` as render --frames writes it.
  std::vector<unsigned char> frame(const QString& scene, int frame) {
    const QString out = path(QFileInfo(scene).baseName() + "_%03d.png");
    const Run r = cli({"render", scene, "--frames", QString("%1-%1").arg(frame), "--size", "64x36", "--out", out,
                       "--aa", "none"});
    if (r.code != 0) qWarning("%s", qPrintable(r.err));
    return pixels(path(QString("%1_%2.png").arg(QFileInfo(scene).baseName()).arg(frame, 3, 10, QChar('0'))));
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QFile obj(path("box.obj"));
    QVERIFY(obj.open(QIODevice::WriteOnly));
    obj.write(kBox);
    obj.close();
    Run r = cli({"new", path("base.hscene")});
    QCOMPARE(r.code, 0);
    r = cli({"import", path("box.obj"), path("base.hscene")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
  }

  void keysAnimateWhatRenderDraws() {
    fs::copy_file(path("base.hscene").toStdString(), path("anim.hscene").toStdString());
    for (const QStringList& k : {QStringList{"--material", kMaterial, "base_color", "0", "0.8,0.8,0.8"},
                                 QStringList{"--material", kMaterial, "base_color", "2", "0.1,0.9,0.1"},
                                 QStringList{"--settings", "exposure_ev100", "0", kDefaultExposure},
                                 QStringList{"--settings", "settings.exposure_ev100", "120f", "13"}}) {
      const Run r = cli(QStringList{"key"} + k + QStringList{path("anim.hscene"), "--interp", "linear"});
      QVERIFY2(r.code == 0, qPrintable(r.err));
      QVERIFY(r.out.contains("keyed"));
    }
    // The values of frame 120 (2 s), set without animation.
    fs::copy_file(path("base.hscene").toStdString(), path("still.hscene").toStdString());
    Run r = cli({"material", "set", kMaterial, "base_color", "0.1,0.9,0.1", path("still.hscene")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"set", "settings.exposure_ev100", "13", path("still.hscene")});
    QVERIFY2(r.code == 0, qPrintable(r.err));

    const auto at0 = frame(path("anim.hscene"), 0);
    const auto at120 = frame(path("anim.hscene"), 120);
    const auto base = frame(path("base.hscene"), 0);
    const auto still = frame(path("still.hscene"), 120);
    QVERIFY(!at0.empty() && !at120.empty());
    QVERIFY(at0 == base);      // the first keys are the scene's own values
    QVERIFY(at120 == still);   // the last keys are what `material set` and `set` give
    QVERIFY(at0 != at120);     // and they change the picture
    // Halfway the picture is neither.
    const auto at60 = frame(path("anim.hscene"), 60);
    QVERIFY(at60 != at0 && at60 != at120);
  }

  void sequenceAndInfoListTheTracks() {
    Run r = cli({"sequence", path("anim.hscene")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("1 animated material, animated settings"), qPrintable(r.out));
    QVERIFY2(r.out.contains("'box / default' (material #") && r.out.contains("material.base_color: 2 keys"),
             qPrintable(r.out));
    QVERIFY2(r.out.contains("settings: settings.exposure_ev100: 2 keys"), qPrintable(r.out));
    r = cli({"info", path("anim.hscene"), "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const QJsonArray tracks = QJsonDocument::fromJson(r.out.toUtf8()).object()["tracks"].toArray();
    QCOMPARE(tracks.size(), 2);
    QCOMPARE(tracks[0].toObject()["material"].toString(), kMaterial);
    QCOMPARE(tracks[0].toObject()["property"].toString(), QString("material.base_color"));
    QCOMPARE(tracks[0].toObject()["keys"].toInt(), 2);
    QCOMPARE(tracks[1].toObject()["settings"].toBool(), true);
    QVERIFY(!tracks[1].toObject().contains("entity_id"));
  }

  void refusals() {
    const QString s = path("base.hscene");
    const std::string before = hs::test::readFile(s.toStdString());
    struct Case {
      QStringList args;
      int code;
      QString says;
    };
    const std::vector<Case> cases = {
        {{"--material", "nope", "roughness", "1", "0.5", s}, 1, "--material: no material named 'nope'"},
        {{"--material", kMaterial, "model", "1", "phong", s}, 1, "'material.model' cannot be animated"},
        {{"--material", kMaterial, "roughness", "1", "1.5", s}, 1, "Roughness must be from 0 to 1"},
        {{"--material", kMaterial, "no_such", "1", "1", s}, 1, "no property 'material.no_such'"},
        {{"--settings", "fog_mode", "1", "1", s}, 1, "'settings.fog_mode' cannot be animated"},
        {{"--settings", "fog_density", "1", "11", s}, 1, "must be from 0 to 10"},
        {{"--settings", "--material", kMaterial, "roughness", "1", "0.5", s}, 2, "give one"},
        {{"--settings", "Camera", "fog_density", "1", "0.1", s}, 2, "expected --settings <field>"},
        // An entity key cannot name a material field.
        {{"Camera", "material.roughness", "1", "0.5", s}, 1, "not a field of an entity"},
    };
    for (const Case& c : cases) {
      const Run r = cli(QStringList{"key"} + c.args);
      QVERIFY2(r.code == c.code && r.err.contains(c.says),
               qPrintable(c.args.join(' ') + QString(": exit %1: ").arg(r.code) + r.err));
    }
    QVERIFY(hs::test::readFile(s.toStdString()) == before);  // nothing was saved
  }
};

QTEST_GUILESS_MAIN(TestCliObjectTracks)
#include "test_cli_object_tracks.moc"
