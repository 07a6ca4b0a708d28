// hybridscape-cli's sequence side as a user runs it (the built program through
// QProcess, the real renderer): render --frames with layouts, resume after a
// real SIGKILL (byte-identical to an uninterrupted run), split runs, full
// and read-only disks (an error naming the frame, finished frames kept),
// direct video, the comfort report, `key` and `sequence`, and a farm run
// acted out with bash (every array task, then the check). The run on a real
// Slurm is tests/farm/test_farm_slurm.cpp.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <sys/mount.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "cli_runner.h"
#include "file_bytes.h"
#include "scene/hscene_file.h"
#include "sequencer/frame_verify.h"
#include "sequencer/image_writer.h"
#include "sequencer/key_edit.h"
#include "sequencer/slurm_script.h"

using namespace hs;
using hs::test::kCli;
namespace fs = std::filesystem;

namespace {

const QString kSize = "64x36";  // per eye
// No MSAA: on llvmpipe a frame of the demo costs its 420,000 triangles, and
// 4x MSAA triples that; what the tests check does not depend on it. For the
// same reason initTestCase clears the demo's foliage (its shadows doubled a
// frame's cost: about 300 ms of 650 in the sun's cascades) and hides its
// particle emitters (each run evaluates the snow cold first); nothing here is
// about them (test_foliage_render, test_particle_render and test_stereo_frames
// draw them; test_farm_slurm renders the whole demo in chunks).
const QStringList kFast = {"--aa", "none"};

using Run = hs::test::CliRun;

// A tmpfs mounted for the test (root only: CI runs as root); unmounted when it goes.
struct TmpfsMount {
  std::string dir;
  bool mounted = false;
  TmpfsMount(const std::string& d, unsigned long flags, const char* options) : dir(d) {
    fs::create_directories(dir);
    mounted = ::geteuid() == 0 && ::mount("tmpfs", dir.c_str(), "tmpfs", flags, options) == 0;
  }
  ~TmpfsMount() {
    if (mounted) ::umount2(dir.c_str(), MNT_DETACH);
  }
};

std::pair<int, int> imageSize(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {0, 0};
  return {in->spec().width, in->spec().height};
}

std::string frameName(const std::string& dir, int f, const char* ext = "png") {
  char name[64];
  std::snprintf(name, sizeof name, "/f_%03d.%s", f, ext);
  return dir + name;
}

// stderr without the progress lines a run longer than 10 s prints when stderr
// is not a terminal ("frame 12: 13/60 done (0 kept), ..."): on failure the
// rest must be one line, the reason, and the last.
QStringList errorLines(const hs::test::CliRun& r) {
  static const QRegularExpression progress("^frame \\d+: \\d+/\\d+ done ");
  const QStringList all = r.errLines();
  QStringList rest;
  for (const QString& l : all)
    if (!progress.match(l).hasMatch()) rest.append(l);
  if (!all.isEmpty() && progress.match(all.back()).hasMatch()) rest.append("(a progress line after the reason)");
  return rest;
}

int countFiles(const std::string& dir, bool temporaries) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (sequencer::isTemporaryName(e.path().filename().string()) == temporaries) ++n;
  return n;
}

}  // namespace

class TestCliSequence : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  QString demo_;
  std::string reference_;  // frames 0-23 of the demo, sbs, one uninterrupted run

  QString path(const QString& name) const { return tmp_.filePath(name); }
  std::string dir(const QString& name) const { return path(name).toStdString(); }

  Run cli(const QStringList& args, int timeoutMs = 120000) { return test::runCli(args, tmp_.path(), timeoutMs); }

  void expectError(const QStringList& args, int code, const QStringList& names) {
    const Run r = cli(args);
    const QString cmd = "hybridscape-cli " + args.join(' ');
    QVERIFY2(r.code == code, qPrintable(QString("%1: exit %2, expected %3; stderr: %4").arg(cmd).arg(r.code).arg(code).arg(r.err)));
    QVERIFY2(errorLines(r).size() == 1 && r.err.endsWith('\n'),
             qPrintable(QString("%1: expected one line on stderr, got:\n%2").arg(cmd, r.err)));
    for (const QString& n : names)
      QVERIFY2(r.err.contains(n), qPrintable(QString("%1: '%2' not in: %3").arg(cmd, n, r.err)));
  }

  QStringList render(const QString& out, const QString& frames, const QStringList& more = {}) {
    return QStringList{"render", demo_, "--frames", frames, "--size", kSize, "--out", out} + kFast + more;
  }

  // Every frame of `frames` in `d` has the reference's bytes.
  bool sameAsReference(const std::string& d, int first, int last, QString& why) {
    for (int f = first; f <= last; ++f) {
      const std::string a = test::readFile(frameName(reference_, f)), b = test::readFile(frameName(d, f));
      if (a.empty() || a != b) {
        why = QString("frame %1 %2").arg(f).arg(b.empty() ? "is missing" : "differs from the uninterrupted run");
        return false;
      }
    }
    return true;
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
    demo_ = path("demo.hscene");
    Run r = cli({"demo", demo_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"info", demo_, "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const QJsonArray types = QJsonDocument::fromJson(r.out.toUtf8()).object()["foliage"].toObject()["types"].toArray();
    QVERIFY2(!types.isEmpty(), "the demo has no foliage types any more: drop the clearing here");
    for (const QJsonValue& t : types) {
      r = cli({"foliage", "clear", t.toObject()["name"].toString(), demo_});
      QVERIFY2(r.code == 0, qPrintable(r.err));
    }
    r = cli({"info", demo_, "--json"});
    const QJsonArray emitters = QJsonDocument::fromJson(r.out.toUtf8()).object()["particles"].toObject()["emitters"].toArray();
    QVERIFY2(!emitters.isEmpty(), "the demo has no particles any more: drop the hiding here");
    for (const QJsonValue& e : emitters) {
      r = cli({"set", QString::number(e.toObject()["entity"].toInteger()), "entity.visible", "false", demo_});
      QVERIFY2(r.code == 0, qPrintable(r.err));
    }
    reference_ = dir("reference");
    r = cli(render(QString::fromStdString(reference_) + "/f_%03d.png", "0-23"));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("rendered 24 frame(s), kept 0, of 24"), qPrintable(r.out));
    QVERIFY(r.out.contains("camera 'Flight Camera'"));
  }

  void demoGivesAMovingSideBySideSequence() {
    const auto [w, h] = imageSize(frameName(reference_, 0));
    QCOMPARE(w, 128);
    QCOMPARE(h, 36);
    QVERIFY(test::readFile(frameName(reference_, 0)) != test::readFile(frameName(reference_, 23)));
    // The stereo pair: the left half differs from the right half.
    auto in = OIIO::ImageInput::open(frameName(reference_, 12));
    QVERIFY(in);
    std::vector<uint8_t> px(size_t(w) * size_t(h) * 3);
    QVERIFY(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    int differing = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w / 2; ++x)
        for (int c = 0; c < 3; ++c)
          differing += px[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)] !=
                       px[(size_t(y) * size_t(w) + size_t(x + w / 2)) * 3 + size_t(c)];
    QVERIFY(differing > 0);
  }

  void layouts_data() {
    QTest::addColumn<QString>("layout");
    QTest::addColumn<int>("width");
    QTest::addColumn<int>("height");
    QTest::addColumn<int>("files");
    QTest::newRow("sbs") << "sbs" << 128 << 36 << 1;
    QTest::newRow("sbs-squeezed") << "sbs-squeezed" << 64 << 36 << 1;
    QTest::newRow("tb") << "tb" << 64 << 72 << 1;
    QTest::newRow("separate") << "separate" << 64 << 36 << 2;
    QTest::newRow("anaglyph") << "anaglyph" << 64 << 36 << 1;
    QTest::newRow("mono") << "mono" << 64 << 36 << 1;
  }
  void layouts() {
    QFETCH(QString, layout);
    QFETCH(int, width);
    QFETCH(int, height);
    QFETCH(int, files);
    const std::string d = dir("layout-" + layout);
    const Run r = cli(render(QString::fromStdString(d) + "/f_%03d.jpg", "100-101", {"--layout", layout, "--quality", "80"}));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QCOMPARE(countFiles(d, false), 2 * files);
    const std::string first = files == 2 ? d + "/f_100_left.jpg" : frameName(d, 100, "jpg");
    const auto [w, h] = imageSize(first);
    QCOMPARE(w, width);
    QCOMPARE(h, height);
  }

  void resumeKeepsValidFramesAndOverwriteRedoes() {
    const std::string d = dir("resume");
    const QString out = QString::fromStdString(d) + "/f_%03d.png";
    Run r = cli(render(out, "0-11"));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    fs::remove(frameName(d, 4));
    test::writeFile(frameName(d, 7), "not an image");
    // Issue 10: a frame cut to half its size was kept among the valid ones
    // (and `farm verify` passed it unless --deep).
    fs::resize_file(frameName(d, 9), fs::file_size(frameName(d, 9)) / 2);
    r = cli({"farm", "verify", "--frames", "8-11", "--out", out, "--size", kSize});
    QVERIFY2(r.code == 1, qPrintable(r.out + r.err));
    QVERIFY2(r.out.contains("3 of 4 frames valid") && r.out.contains("invalid frame 9: ") && r.out.contains("damaged"),
             qPrintable(r.out));
    r = cli(render(out, "0-11"));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("rendered 3 frame(s), kept 9, of 12"), qPrintable(r.out));
    QVERIFY2(r.out.contains("rendering again 2 invalid frame(s) of an earlier run"), qPrintable(r.out));
    QVERIFY2(r.out.contains("frame 7: ") && r.out.contains("frame 9: "), qPrintable(r.out));
    r = cli({"farm", "verify", "--frames", "0-11", "--out", out, "--size", kSize});
    QVERIFY2(r.code == 0 && r.out.contains("12 of 12 frames valid"), qPrintable(r.out + r.err));
    QString why;
    QVERIFY2(sameAsReference(d, 0, 11, why), qPrintable(why));
    // A changed scene is not mixed with old frames: its tag differs.
    const QString changed = path("changed.hscene");
    QVERIFY(QFile::copy(demo_, changed));
    r = cli({"set", "Main Camera", "camera.fov_deg", "35", changed});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli(QStringList{"render", changed, "--frames", "0-11", "--size", kSize, "--out", out} + kFast);
    QVERIFY2(r.out.contains("rendered 12 frame(s), kept 0"), qPrintable(r.out));
    r = cli(render(out, "0-11", {"--overwrite"}));
    QVERIFY2(r.out.contains("rendered 12 frame(s), kept 0"), qPrintable(r.out));
    QVERIFY2(sameAsReference(d, 0, 11, why), qPrintable(why));
  }

  void splitRunsAreByteIdenticalToOneRun() {
    // Two separate processes, the later half first.
    const std::string d = dir("split");
    const QString out = QString::fromStdString(d) + "/f_%03d.png";
    Run r = cli(render(out, "12-23"));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli(render(out, "0-11"));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QString why;
    QVERIFY2(sameAsReference(d, 0, 23, why), qPrintable(why));
  }

  void killedMidFrameThenResumed() {
    // SIGKILL a real export while it renders and writes; what is left under
    // final names is whole, and running again completes the sequence with
    // the bytes of the uninterrupted run. Larger frames with MSAA: slower,
    // so the kill lands in the middle.
    const std::string d = dir("killed");
    const QString out = QString::fromStdString(d) + "/f_%03d.png";
    const QStringList args = {"render", demo_, "--frames", "0-15", "--size", "256x144", "--out", out};
    QProcess p;
    p.setWorkingDirectory(tmp_.path());
    p.start(kCli, args);
    QVERIFY(p.waitForStarted());
    QElapsedTimer t;
    t.start();
    while (countFiles(d, false) < 5 && t.elapsed() < 60000 && p.state() == QProcess::Running) QTest::qWait(2);
    QVERIFY2(p.state() == QProcess::Running, "the export ended before it could be killed");
    p.kill();  // SIGKILL: no handler runs
    p.waitForFinished();
    const int before = countFiles(d, false);
    qInfo("killed with %d whole frames and %d temporary file(s) on disk", before, countFiles(d, true));
    QVERIFY(before >= 5 && before < 16);
    for (const auto& e : fs::directory_iterator(d)) {
      const std::string name = e.path().filename().string();
      if (sequencer::isTemporaryName(name)) continue;
      const sequencer::FrameCheck c = sequencer::checkFrameFile(e.path().string(), 512, 144, {}, true);
      QVERIFY2(c.ok, c.problem.c_str());
    }
    const Run r = cli(args);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains(QString("kept %1, of 16").arg(before)), qPrintable(r.out));
    QCOMPARE(countFiles(d, true), 0);
    QCOMPARE(countFiles(d, false), 16);
    // Byte-identical to an uninterrupted run.
    const std::string whole = dir("killed-reference");
    QStringList again = args;
    again[7] = QString::fromStdString(whole) + "/f_%03d.png";
    const Run u = cli(again);
    QVERIFY2(u.code == 0, qPrintable(u.err));
    for (int f = 0; f < 16; ++f)
      QVERIFY2(test::readFile(frameName(d, f)) == test::readFile(frameName(whole, f)),
               qPrintable(QString("frame %1 differs after resume").arg(f)));
  }

  void fullDiskNamesTheFrameAndKeepsWhatWasWritten() {
    if (::geteuid() != 0) QSKIP("needs root to mount a small tmpfs");
    TmpfsMount disk(dir("full"), 0, "size=120k");
    QVERIFY(disk.mounted);
    const QString out = QString::fromStdString(disk.dir) + "/f_%03d.png";
    const Run r = cli(render(out, "0-59", {"--size", "96x54"}));
    QCOMPARE(r.code, 1);
    const QStringList lines = errorLines(r);
    QVERIFY2(lines.size() == 1, qPrintable(r.err));
    qInfo("%s", qPrintable(lines[0]));
    QRegularExpressionMatch m = QRegularExpression("frame (\\d+): ").match(lines[0]);
    QVERIFY2(m.hasMatch(), qPrintable(lines[0]));
    QVERIFY(lines[0].contains("disk full"));
    const int failed = m.captured(1).toInt();
    QVERIFY(failed > 0 && failed < 59);
    QVERIFY2(r.out.contains("are kept; run the export again to resume"), qPrintable(r.out));
    for (int f = 0; f < failed; ++f) {
      const sequencer::FrameCheck c = sequencer::checkFrameFile(frameName(disk.dir, f), 192, 54, {}, true);
      QVERIFY2(c.ok, qPrintable(QString("frame %1 before the failure: %2").arg(f).arg(c.problem.c_str())));
    }
    QCOMPARE(countFiles(disk.dir, true), 0);
  }

  void unwritableFolderNamesTheFrame() {
    // A folder under a file: no one can write there, root included.
    test::writeFile(dir("plainfile"), "x");
    expectError(render(path("plainfile") + "/f_%03d.png", "3-5"), 1, {"frame 3", "plainfile"});
    if (::geteuid() != 0) QSKIP("needs root to mount a read-only tmpfs");
    TmpfsMount ro(dir("readonly"), MS_RDONLY, "size=1m");
    QVERIFY(ro.mounted);
    expectError(render(QString::fromStdString(ro.dir) + "/f_%03d.png", "7-9"), 1, {"frame 7", "read-only"});
  }

  void directVideoWithStereoMetadata() {
    if (QStandardPaths::findExecutable("ffmpeg").isEmpty()) QSKIP("ffmpeg is not installed");
    const QString film = path("flight.mkv");
    const Run r = cli(QStringList{"render", demo_, "--frames", "0-11", "--size", kSize, "--video", film, "--codec", "h264"} + kFast);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(QFileInfo(film).size() > 0);
    if (QStandardPaths::findExecutable("ffprobe").isEmpty()) return;
    QProcess probe;
    probe.start("ffprobe", {"-v", "error", "-count_frames", "-show_streams", "-select_streams", "v:0", film});
    QVERIFY(probe.waitForFinished(30000));
    const QString info = QString::fromUtf8(probe.readAllStandardOutput());
    QVERIFY2(info.contains("nb_read_frames=12"), qPrintable(info));
    QVERIFY2(info.contains("width=128") && info.contains("height=36"), qPrintable(info));
    QVERIFY2(info.contains("side by side"), qPrintable(info));
  }

  void comfortReportFlagsFramesOutsideTheBudget() {
    const QString out = path("comfort") + "/f_%03d.png";
    Run r = cli(render(out, "0-599x150", {"--comfort"}));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("frame 0: nearest -") && r.out.contains("at infinity (sky)"), qPrintable(r.out));
    QVERIFY2(r.out.contains("comfort: 0 of 4 frame(s) outside the budget -1.00% .. +2.00%"), qPrintable(r.out));
    r = cli(render(out, "0-599x150", {"--comfort", "--budget", "-0.2,0.5"}));
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("OUTSIDE BUDGET") && r.out.contains("comfort: 4 of 4 frame(s) outside the budget -0.20% "
                                                                 ".. +0.50%: 0-450x150"),
             qPrintable(r.out));
  }

  void keyAndSequenceCommands() {
    const QString scene = path("keys.hscene");
    QVERIFY(QFile::copy(demo_, scene));
    Run r = cli({"key", "Main Camera", "camera.fov_deg", "0", "50", scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"key", "Main Camera", "camera.fov_deg", "120f", "30", scene, "--interp", "linear"});
    QVERIFY2(r.code == 0 && r.out.contains("the track has 2 key(s)"), qPrintable(r.out + r.err));
    r = cli({"key", "Stanford Bunny", "transform.rotation_deg", "1.5", "0,0,200", scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"key", "Stanford Bunny", "entity.visible", "3", "false", scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    std::string error;
    auto s = scene::loadScene(scene.toStdString(), error);
    QVERIFY2(s, error.c_str());
    const scene::EntityId cam = s->findByName("Main Camera"), bunny = s->findByName("Stanford Bunny");
    QCOMPARE(sequencer::keyTimes(s->sequence, cam, "camera.fov_deg"), (std::vector<double>{0.0, 2.0}));
    QCOMPARE(sequencer::keyTimes(s->sequence, bunny, "transform.rotation").size(), size_t(1));
    QCOMPARE(sequencer::keyTimes(s->sequence, bunny, "entity.visible"), std::vector<double>{3.0});
    const auto* fov = std::get_if<sequencer::ScalarTrack>(&s->sequence.findBinding(cam)->tracks[0]);
    QVERIFY(fov);
    QCOMPARE(fov->keys[0].interpolation, sequencer::Interpolation::Cubic);
    QCOMPARE(fov->keys[1].interpolation, sequencer::Interpolation::Linear);
    QCOMPARE(fov->keys[1].value, 30.0);
    // A key at an existing time replaces the value.
    r = cli({"key", "Main Camera", "camera.fov_deg", "2", "25", scene});
    QVERIFY2(r.code == 0 && r.out.contains("the track has 2 key(s)"), qPrintable(r.out + r.err));

    r = cli({"sequence", scene});
    QVERIFY2(r.code == 0 && r.out.contains("60 fps, frames 0-599") && r.out.contains("'Main Camera'"), qPrintable(r.out));
    r = cli({"sequence", scene, "--fps", "30", "--range", "0-299"});
    QVERIFY2(r.code == 0 && r.out.contains("30 fps, frames 0-299 (300 frames, 10.00 s)"), qPrintable(r.out + r.err));
    s = scene::loadScene(scene.toStdString(), error);
    QCOMPARE(s->sequence.rate, (sequencer::FrameRate{30, 1}));
    QCOMPARE(s->sequence.endFrame, int64_t(299));
    r = cli({"sequence", scene, "--fps", "59.94"});
    QVERIFY2(r.out.contains("59.94 fps (60000/1001)"), qPrintable(r.out));
  }

  void keyAndSequenceErrors() {
    const QString scene = path("keys-bad.hscene");
    QVERIFY(QFile::copy(demo_, scene));
    const QByteArray before = QByteArray::fromStdString(test::readFile(scene.toStdString()));
    expectError({"key", "Nobody", "camera.fov_deg", "0", "50", scene}, 1, {"Nobody"});
    expectError({"key", "Main Camera", "camera.zoom", "0", "50", scene}, 1, {"camera.zoom"});
    expectError({"key", "Main Camera", "entity.name", "0", "x", scene}, 1, {"entity.name", "cannot be animated"});
    expectError({"key", "Main Camera", "camera.fov_deg", "soon", "50", scene}, 2, {"soon"});
    expectError({"key", "Main Camera", "camera.fov_deg", "0", "wide", scene}, 1, {"wide"});
    expectError({"key", "Sun", "camera.fov_deg", "0", "50", scene}, 1, {"Sun", "camera"});
    expectError({"key", "Main Camera", "camera.fov_deg", "0", "50", scene, "--interp", "bouncy"}, 2, {"bouncy"});
    expectError({"sequence", scene, "--fps", "fast"}, 2, {"fast"});
    expectError({"sequence", scene, "--range", "10-5"}, 2, {"10-5"});
    expectError({"sequence", path("nope.hscene")}, 1, {"nope.hscene"});
    QCOMPARE(QByteArray::fromStdString(test::readFile(scene.toStdString())), before);  // untouched
  }

  void renderErrors() {
    const QString out = path("err") + "/f_%03d.png";
    expectError(render(out, "5-x"), 2, {"--frames", "5-x"});
    expectError(render(out, "0-3", {"--layout", "diagonal"}), 2, {"diagonal", "sbs"});
    expectError(render(path("err/plain.png"), "0-3"), 1, {"plain.png"});  // no frame number in the name
    expectError(render(out, "0-3", {"--camera", "Drone"}), 1, {"Drone", "Flight Camera"});
    expectError(render(out, "0-3", {"--budget", "2,-1"}), 2, {"--budget"});
    expectError(render(out, "0-3", {"--video", path("f.mp4")}), 2, {"--video"});
    expectError({"render", demo_, "--frames", "0-3", "--video", path("f.avi")}, 1, {"f.avi", ".mp4"});
    expectError({"render", demo_, "--frames", "0-3", "--layout", "separate", "--video", path("f.mp4")}, 1, {"separate"});
    expectError(render(out, "0-3", {"--png16", "--out", path("err/f_%03d.jpg")}), 2, {"--png16"});
    expectError(render(out, "0-3", {"--fps", "0"}), 2, {"--fps"});
    expectError({"render", path("missing.hscene"), "--frames", "0-3", "--out", out}, 1, {"missing.hscene"});
  }

  // One frame at a time of the timeline (render --at): the flight camera
  // has moved by t = 2 s, the same t gives the same bytes, and --at belongs
  // to one frame only.
  void oneFrameAtATime() {
    auto one = [&](const QString& file, const QString& at) {
      QStringList a{"render", demo_, "--out", path(file), "--size", "96x54", "--camera", "Flight Camera"};
      if (!at.isEmpty()) a << "--at" << at;
      const Run r = cli(a);
      QVERIFY2(r.code == 0, qPrintable(r.err));
    };
    one("at0.png", "0");
    one("at2.png", "2");
    one("at2_again.png", "2");
    one("document.png", "");
    const std::string at0 = test::readFile(path("at0.png").toStdString()),
                      at2 = test::readFile(path("at2.png").toStdString());
    QVERIFY(!at0.empty() && !at2.empty());
    QVERIFY(at2 != at0);  // the camera flew on
    QCOMPARE(test::readFile(path("at2_again.png").toStdString()), at2);
    expectError({"render", demo_, "--out", path("x.png"), "--at", "-1"}, 2, {"--at"});
    expectError(render(path("err") + "/f_%03d.png", "0-3", {"--at", "2"}), 2, {"--at", "one frame"});
  }

  void farmSlurmScriptsActedOutWithBash() {
    // What Slurm would do, without Slurm: every array task of render.sbatch
    // (SLURM_ARRAY_TASK_ID), then verify.sbatch; a lost frame is reported
    // with the task to re-run, and re-running it repairs the run.
    const std::string work = dir("farm work");  // a space in the name
    const QString frames = QString::fromStdString(work) + "/frames/f_%03d.png";
    Run r = cli(QStringList{"farm", "slurm", demo_, "--frames", "0-29", "--chunk", "8", "--layout", "sbs", "--size", kSize,
                            "--out", frames, "--dir", QString::fromStdString(work), "--partition", "local"} + kFast);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("4 array task(s) of up to 8 frames, 30 frames"), qPrintable(r.out));
    const std::string script = test::readFile(work + "/render.sbatch");
    QVERIFY(script.find("#SBATCH --array=0-3\n") != std::string::npos);
    QVERIFY(script.find("#SBATCH --partition=local\n") != std::string::npos);
    QVERIFY2(script.find(QFileInfo(kCli).canonicalFilePath().toStdString() + " render " +
                         sequencer::shellQuote(QFileInfo(demo_).absoluteFilePath().toStdString())) != std::string::npos,
             script.c_str());
    auto bash = [&](const std::string& file, const QStringList& env, int& code) {
      QProcess p;
      p.setProcessChannelMode(QProcess::MergedChannels);
      QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
      for (const QString& kv : env) e.insert(kv.section('=', 0, 0), kv.section('=', 1));
      p.setProcessEnvironment(e);
      p.setWorkingDirectory("/");
      p.start("bash", {QString::fromStdString(file)});
      p.waitForFinished(120000);
      code = p.exitCode();
      return QString::fromUtf8(p.readAll());
    };
    int code = 0;
    for (int task = 0; task < 4; ++task) {
      const QString log = bash(work + "/render.sbatch", {QString("SLURM_ARRAY_TASK_ID=%1").arg(task), "SLURM_ARRAY_JOB_ID=1"}, code);
      QVERIFY2(code == 0, qPrintable(log));
    }
    QString log = bash(work + "/verify.sbatch", {}, code);
    QVERIFY2(code == 0 && log.contains("30 of 30 frames valid"), qPrintable(log));
    // The farm's frames are the single machine's (reference_ holds 0-23).
    for (int f = 0; f < 24; ++f)
      QVERIFY(test::readFile(frameName(work + "/frames", f)) == test::readFile(frameName(reference_, f)));
    fs::remove(frameName(work + "/frames", 17));
    log = bash(work + "/verify.sbatch", {}, code);
    QCOMPARE(code, 1);
    QVERIFY2(log.contains("missing frames: 17") && log.contains("chunks (job-array tasks) to run again: 2"), qPrintable(log));
    log = bash(work + "/render.sbatch", {"SLURM_ARRAY_TASK_ID=2", "SLURM_ARRAY_JOB_ID=1"}, code);
    QVERIFY2(code == 0 && log.contains("rendered 1 frame(s), kept 7, of 8"), qPrintable(log));
    bash(work + "/verify.sbatch", {}, code);
    QCOMPARE(code, 0);
  }

  void farmErrors() {
    expectError({"farm", "slurm", demo_, "--frames", "0-9", "--out", path("v.mp4")}, 2, {"image sequences"});
    expectError({"farm", "slurm", demo_, "--frames", "0-9", "--out", path("f_%03d.png"), "--chunk", "0"}, 2, {"--chunk"});
    expectError({"farm", "slurm", demo_, "--out", path("f.png")}, 2, {"--out"});
    expectError({"farm", "verify", "--frames", "0-3", "--out", path("none") + "/f_%03d.png", "--size", kSize}, 1,
                {"4 frame(s) missing", "0-3"});
    expectError({"farm", "verify", "--out", path("none") + "/f_%03d.png"}, 2, {"--frames"});
    expectError({"farm", "bake"}, 2, {"bake"});
  }
};

QTEST_GUILESS_MAIN(TestCliSequence)
#include "test_cli_sequence.moc"
