// `hybridscape-cli path` as a user runs it (the built program through
// QProcess): a path made with look-at, then `render` of two frames whose
// camera positions (through scene::animatedState, what render evaluates)
// lie on the path and have moved along it; constant speed within 0.5%;
// changing the aim (entity, along), banking, timing and points of an existing
// path; --clear; --help; and one-line errors for bad input, which leave the
// scene file as it was.
#include <QTemporaryDir>
#include <QtTest>

#include "cli_runner.h"
#include "file_bytes.h"
#include "scene/animation.h"
#include "scene/camera_path_edits.h"
#include "scene/hscene_file.h"

using namespace hs;

namespace {

using Run = hs::test::CliRun;

glm::dvec3 cameraAt(const scene::SceneState& s, scene::EntityId id, double t) {
  const scene::SceneState at = scene::animatedState(s, scene::compileSequence(s), t);
  return glm::dvec3(at.worldMatrix(id)[3]);
}

}  // namespace

class TestCliPath : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  QString scene_;

  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }

  scene::SceneState load() {
    std::string error;
    auto s = scene::loadScene(scene_.toStdString(), error);
    if (!s) qFatal("%s", error.c_str());
    return *s;
  }

  void expectError(const QStringList& args, int code, const QString& says) {
    const std::string before = test::readFile(scene_.toStdString());
    const Run r = cli(QStringList{"path"} + args);
    const QString cmd = "hybridscape-cli path " + args.join(' ');
    QVERIFY2(r.code == code, qPrintable(QString("%1: exit %2, expected %3; %4").arg(cmd).arg(r.code).arg(code).arg(r.err)));
    QVERIFY2(r.err.count('\n') == 1 && r.err.endsWith('\n'), qPrintable(cmd + ": not one line: " + r.err));
    QVERIFY2(r.err.contains(says), qPrintable(cmd + ": '" + says + "' not in: " + r.err));
    QVERIFY2(test::readFile(scene_.toStdString()) == before, qPrintable(cmd + ": the scene file changed"));
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = tmp_.filePath("s.hscene");
    const Run r = cli({"new", scene_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
  }

  void createThenRenderTwoFrames() {
    const Run made = cli({"path", "Camera", scene_, "--points", "0,-10,2; 10,0,3; 4,14,6", "--look-at", "0,0,1",
                          "--start", "0", "--end", "120f"});
    QVERIFY2(made.code == 0, qPrintable(made.err));
    QVERIFY2(made.out.contains("'Camera' follows a path: 3 points"), qPrintable(made.out));
    QVERIFY(made.out.contains("aim: at the point 0,0,1"));
    QVERIFY(made.out.contains("constant speed"));
    const scene::SceneState s = load();
    const scene::EntityId cam = s.findByName("Camera");
    const sequencer::PathFollow* f = scene::findPath(s, cam);
    QVERIFY(f);
    QCOMPARE(f->path.points, (std::vector<glm::dvec3>{{0, -10, 2}, {10, 0, 3}, {4, 14, 6}}));
    QCOMPARE(f->aim, sequencer::PathAim::Point);
    QCOMPARE(f->progress, sequencer::constantSpeedProgress(0.0, 2.0));

    // Two frames rendered headless through the camera.
    const Run r = cli({"render", scene_, "--frames", "0,60", "--camera", "Camera", "--layout", "mono", "--size",
                       "64x36", "--aa", "none", "--out", "f/f_%03d.png"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const std::string a = test::readFile(tmp_.filePath("f/f_000.png").toStdString());
    const std::string b = test::readFile(tmp_.filePath("f/f_060.png").toStdString());
    QVERIFY(!a.empty() && !b.empty());
    QVERIFY(a != b);
    // Where the camera was for those frames (the function render evaluates):
    // at the start of the path, then half its length along it.
    const sequencer::PathSampler path(f->path.points);
    const glm::dvec3 p0 = cameraAt(s, cam, sequencer::frameTime(0, s.sequence.rate));
    const glm::dvec3 p60 = cameraAt(s, cam, sequencer::frameTime(60, s.sequence.rate));
    qInfo("frame 0 at (%.3f, %.3f, %.3f), frame 60 at (%.3f, %.3f, %.3f); path %.3f m", p0.x, p0.y, p0.z, p60.x, p60.y,
          p60.z, path.length());
    QVERIFY(glm::length(p0 - glm::dvec3(0, -10, 2)) < 1e-9);
    QVERIFY(glm::length(p60 - path.position(0.5 * path.length())) < 1e-9);
    QVERIFY(glm::length(p60 - p0) > 10.0);
    QVERIFY(glm::length(cameraAt(s, cam, 2.0) - glm::dvec3(4, 14, 6)) < 1e-9);
    // Looking at the target in both frames.
    for (double t : {0.0, 1.0}) {
      const scene::SceneState at = scene::animatedState(s, scene::compileSequence(s), t);
      const glm::dvec3 forward = -glm::dvec3(at.worldMatrix(cam)[2]);
      const glm::dvec3 want = glm::normalize(glm::dvec3(0, 0, 1) - glm::dvec3(at.worldMatrix(cam)[3]));
      QVERIFY(glm::dot(glm::normalize(forward), want) > 1.0 - 1e-9);
    }
  }

  void speedIsConstant() {
    const scene::SceneState s = load();
    const scene::EntityId cam = s.findByName("Camera");
    const sequencer::CompiledSequence compiled = scene::compileSequence(s);
    const double length = sequencer::PathSampler(scene::findPath(s, cam)->path.points).length();
    const double dt = 1.0 / 240.0;
    double worst = 0.0;
    glm::dvec3 prev = cameraAt(s, cam, 0.0);
    for (int i = 1; i <= 480; ++i) {
      const glm::dvec3 p = glm::dvec3(scene::animatedState(s, compiled, i * dt).worldMatrix(cam)[3]);
      worst = std::max(worst, std::abs(glm::length(p - prev) / dt - length / 2.0) / (length / 2.0));
      prev = p;
    }
    qInfo("speed over 2 s, 480 samples: largest deviation from %.4f m/s is %.3g", length / 2.0, worst);
    QVERIFY2(worst < 0.005, qPrintable(QString::number(worst)));
  }

  void changeAnExistingPath() {
    Run r = cli({"path", "Camera", scene_, "--look-at-entity", "Sun", "--bank", "25"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    scene::SceneState s = load();
    const scene::EntityId cam = s.findByName("Camera");
    const sequencer::PathFollow* f = scene::findPath(s, cam);
    QCOMPARE(f->aim, sequencer::PathAim::Entity);
    QCOMPARE(f->targetEntity, s.findByName("Sun"));
    QVERIFY(f->bank);
    QCOMPARE(f->maxBankDeg, 25.0);
    QCOMPARE(f->path.points.size(), size_t(3));  // kept
    QCOMPARE(f->progress, sequencer::constantSpeedProgress(0.0, 2.0));

    r = cli({"path", "Camera", scene_, "--look-along", "--bank", "0", "--end", "4", "--ease"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    s = load();
    f = scene::findPath(s, cam);
    QCOMPARE(f->aim, sequencer::PathAim::Tangent);
    QVERIFY(!f->bank);
    QCOMPARE(f->progress, sequencer::constantSpeedProgress(0.0, 4.0, sequencer::Ease::InOut));

    r = cli({"path", "Camera", scene_, "--points", "1,1,1;2,2,2;3,3,5;4,0,1"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QCOMPARE(scene::findPath(load(), cam)->path.points.size(), size_t(4));
    r = cli({"path", "Camera", scene_});  // shows it
    QVERIFY(r.code == 0 && r.out.contains("4 points") && r.out.contains("  4  4,0,1"));
  }

  void errorsAreOneLine() {
    expectError({"Nobody", scene_, "--points", "0,0,0;1,1,1"}, 1, "no entity named or numbered 'Nobody'");
    expectError({"Camera", scene_, "--points", "0,0,0;1,1"}, 2, "--points: point 2");
    expectError({"Camera", scene_, "--points", "0,0,0"}, 2, "at least two points");
    expectError({"Camera", scene_, "--points", "1,1,1;1,1,1"}, 1, "no length");
    expectError({"Camera", scene_, "--look-at", "1,2,3", "--look-at-entity", "Sun"}, 2, "give one of");
    expectError({"Camera", scene_, "--look-at-entity", "Camera"}, 1, "cannot look at itself");
    expectError({"Camera", scene_, "--look-at-entity", "Moon"}, 1, "no entity named or numbered 'Moon'");
    expectError({"Camera", scene_, "--bank", "120"}, 2, "0 to 90");
    expectError({"Camera", scene_, "--bank", "steep"}, 2, "--bank takes a number");
    expectError({"Camera", scene_, "--start", "5", "--end", "2"}, 2, "--end must be after --start");
    expectError({"Camera", scene_, "--start", "1.5f"}, 2, "not a whole frame");
    expectError({"Camera", scene_, "--clear", "--bank", "3"}, 2, "--clear takes no other options");
    expectError({"Sun", scene_, "--bank", "10"}, 1, "'Sun' follows no path yet");
    expectError({"Sun", scene_, "--clear"}, 1, "'Sun' follows no path");
    expectError({"Camera", tmp_.filePath("missing.hscene"), "--clear"}, 1, "missing.hscene");
    expectError({"Camera"}, 2, "expected <entity> <scene.hscene>");
  }

  void clearAndHelp() {
    const Run help = cli({"path", "--help"});
    QVERIFY(help.code == 0 && help.out.startsWith("usage: hybridscape-cli path <entity> <scene.hscene>"));
    QVERIFY(cli({"--help"}).out.contains("path"));
    const Run r = cli({"path", "Camera", scene_, "--clear"});
    QVERIFY2(r.code == 0 && r.out.contains("no longer follows a path"), qPrintable(r.err));
    const scene::SceneState s = load();
    QVERIFY(!scene::findPath(s, s.findByName("Camera")));
    QVERIFY(s.sequence.bindings.empty());
  }
};

QTEST_GUILESS_MAIN(TestCliPath)
#include "test_cli_path.moc"
