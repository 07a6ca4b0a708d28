// Camera cuts through the real program (tests/common/cli_runner.h): `cut
// add|list|remove`, the cuts in `info`, and `render --frames` following
// them: a frame inside a cut is that camera's frame exactly (against
// `--camera`), a crossfade's first frame is the shot before exactly, its
// last the next shot exactly, the frames between lie between the two and
// are identical in separate runs and split ranges; a dip to black is black
// at its middle. Unsound cuts (reversed,
// overlapping, a transition longer than its shots or after a gap, a cut on
// a light, a cut whose camera was deleted) are refused with the cut named
// and the file left as it was.
#include <QTemporaryDir>
#include <QtTest>

#include "cli_runner.h"
#include "file_pixels.h"
#include "file_bytes.h"
#include "look_from.h"
#include "mesh/primitives.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene_parts.h"

using namespace hs;

namespace {

std::vector<unsigned char> pixels(const QString& path) { return hs::test::filePixels(path.toStdString()); }

// Two cameras looking at two differently coloured boxes; 10 frames a second.
scene::SceneState twoShots() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.sequence.rate = {10, 1};
  s.sequence.startFrame = 0;
  s.sequence.endFrame = 39;
  test::addMeshAsset(s, 1, "Ground", mesh::gridPlane(40.0f, 1), {0.4f, 0.4f, 0.38f});
  test::addMeshEntity(s, 1, "Ground", 1);
  test::addMeshAsset(s, 2, "Red", mesh::uvSphere(1.0f, 16, 8), {0.8f, 0.1f, 0.1f});
  test::addMeshEntity(s, 2, "Red", 2, {-6.0, 0.0, 1.0});
  test::addMeshAsset(s, 3, "Blue", mesh::uvSphere(1.0f, 16, 8), {0.1f, 0.2f, 0.9f});
  test::addMeshEntity(s, 3, "Blue", 3, {6.0, 0.0, 1.0});
  test::addSun(s, 10, {50, 0, -30});
  for (auto [id, name, target] : {std::tuple{20, "A", glm::dvec3(-6, 0, 1)}, std::tuple{21, "B", glm::dvec3(6, 0, 1)}}) {
    scene::Entity cam;
    cam.id = scene::EntityId(id);
    cam.name = name;
    cam.camera = scene::Camera{};
    cam.transform = test::lookFrom(target + glm::dvec3(0, -6, 2), target);
    s.entities[cam.id] = cam;
    s.roots.push_back(cam.id);
  }
  return s;
}

}  // namespace

class TestCliCuts : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString scene_;

  test::CliRun cli(QStringList args) { return test::runCli(args, tmp_.path()); }
  QString path(const QString& name) const { return tmp_.filePath(name); }
  // Frames first..last as `render --frames` writes them (extra arguments after).
  std::vector<std::vector<unsigned char>> frames(const QString& name, int first, int last, QStringList extra = {},
                                                 QString scene = {}) {
    const test::CliRun r = cli(QStringList{"render", scene.isEmpty() ? scene_ : scene, "--frames", QString("%1-%2").arg(first).arg(last),
                                           "--size", "64x36", "--aa", "none", "--out", path(name + "_%03d.png")} +
                               extra);
    if (r.code != 0) qWarning("%s", qPrintable(r.err));
    std::vector<std::vector<unsigned char>> out;
    for (int f = first; f <= last; ++f) out.push_back(pixels(path(QString("%1_%2.png").arg(name).arg(f, 3, 10, QChar('0')))));
    return out;
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = path("cuts.hscene");
    std::string error;
    QVERIFY2(scene::saveScene(twoShots(), scene_.toStdString(), error), error.c_str());
  }

  void addAndList() {
    test::CliRun r = cli({"cut", "add", "A", "0f", "9f", scene_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"cut", "add", "B", "10f", "29f", scene_, "--transition", "crossfade", "--duration", "4f"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("after a crossfade of 4 frames"));
    r = cli({"cut", "list", scene_});
    QVERIFY(r.out.contains("cuts: 2"));
    QVERIFY2(r.out.contains("1  A") && r.out.contains("frames 0-9"), qPrintable(r.out));
    QVERIFY(r.out.contains("2  B") && r.out.contains("frames 10-29") && r.out.contains("crossfade of 4 frames"));
    QVERIFY(!r.out.contains("problem"));
    r = cli({"info", scene_});
    QVERIFY(r.out.contains("cuts: 2"));
    r = cli({"info", scene_, "--json"});
    QVERIFY(r.out.contains("\"cuts\""));
    QVERIFY(r.out.contains("\"transition\":\"crossfade\"") || r.out.contains("\"transition\": \"crossfade\""));
  }

  void framesFollowTheCuts() {
    const auto cut = frames("cut", 8, 16);
    const auto a = frames("a", 8, 16, {"--camera", "A"});
    const auto b = frames("b", 8, 16, {"--camera", "B"});
    QVERIFY(!cut[0].empty() && a[0] != b[0]);
    QVERIFY(cut[0] == a[0] && cut[1] == a[1]);  // frames 8, 9: cut 1's camera
    QVERIFY(cut[2] == a[2]);                    // frame 10: the crossfade's first frame is shot A exactly
    QVERIFY(cut[6] == b[6]);                    // frame 14 (10 + 4): its last is shot B exactly
    QVERIFY(cut[8] == b[8]);                    // after it: B
    // Between: neither, and each channel between the two (the light is
    // mixed before the tone map, so not at the middle of the 8-bit values).
    for (int k : {3, 4, 5}) {
      QVERIFY(cut[size_t(k)] != a[size_t(k)] && cut[size_t(k)] != b[size_t(k)]);
      int outside = 0;
      for (size_t i = 0; i < cut[size_t(k)].size(); ++i) {
        const int lo = std::min(a[size_t(k)][i], b[size_t(k)][i]), hi = std::max(a[size_t(k)][i], b[size_t(k)][i]);
        outside += cut[size_t(k)][i] < lo - 2 || cut[size_t(k)][i] > hi + 2;
      }
      QVERIFY2(outside == 0, qPrintable(QString("frame %1: %2 channels outside the two shots").arg(8 + k).arg(outside)));
    }
    // A split range gives the same transition frame.
    const auto again = frames("again", 12, 12);
    QVERIFY(again[0] == cut[4]);
  }

  // A dip to black: the shot before exactly, black at the middle (both
  // weights 0), the next shot exactly at its end.
  void dipToBlack() {
    test::CliRun r = cli({"cut", "add", "A", "30f", "39f", scene_, "--transition", "dip_to_black", "--duration", "4f",
                          "--ease", "none"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const auto dip = frames("dip", 30, 34);
    const auto a = frames("dip_a", 34, 34, {"--camera", "A"});
    const auto b = frames("dip_b", 30, 30, {"--camera", "B"});
    QVERIFY(dip[0] == b[0]);
    QVERIFY(dip[4] == a[0]);
    int brightest = 0;
    for (size_t i = 0; i < dip[2].size(); ++i)
      if (i % 4 != 3) brightest = std::max(brightest, int(dip[2][i]));
    QCOMPARE(brightest, 0);
    // A quarter in: the shot before at half its light, darker than itself.
    long sumQuarter = 0, sumBefore = 0;
    for (size_t i = 0; i < dip[1].size(); ++i)
      if (i % 4 != 3) sumQuarter += dip[1][i], sumBefore += b[0][i];
    QVERIFY(sumQuarter > 0 && sumQuarter < sumBefore);
  }

  void unsoundCutsAreRefused() {
    const std::string before = test::readFile(scene_.toStdString());
    struct Case {
      QStringList args;
      QString says;
    } cases[] = {
        {{"A", "5f", "12f"}, "overlaps cut 1 (frames 0-9)"},
        {{"A", "40f", "35f"}, "its end is before its start"},
        {{"B", "40f", "45f", "--transition", "dip_to_black", "--duration", "10f"}, "longer than this shot"},
        {{"B", "42f", "49f", "--transition", "crossfade", "--duration", "2f"}, "needs cut 3 to end on frame 41"},
        {{"Sun", "30f", "35f"}, "is not a camera"},
        {{"B", "30f", "35f", "--transition", "crossfade"}, "needs --duration"},
    };
    for (const Case& c : cases) {
      const test::CliRun r = cli(QStringList{"cut", "add"} + c.args.mid(0, 3) + QStringList{scene_} + c.args.mid(3));
      QVERIFY2(r.code != 0 && r.err.contains(c.says), qPrintable(c.args.join(' ') + ": " + r.err));
      QVERIFY(test::readFile(scene_.toStdString()) == before);
    }
  }

  void aDeletedCameraIsNamedWhenRendering() {
    const QString copy = path("deleted.hscene");
    std::string error;
    std::optional<scene::SceneState> s = scene::loadScene(scene_.toStdString(), error);
    QVERIFY(s);
    scene::Document doc;
    doc.reset(std::move(*s), copy);
    {
      scene::Edit e(doc, "Delete B");
      e.removeEntity(doc.state().findByName("B"));
      QVERIFY(e.commit());
    }
    QVERIFY(scene::saveScene(doc.state(), copy.toStdString(), error));
    QVERIFY2(doc.state().sequence.cuts.size() == 3, "the cut stays (nothing lost), named when rendered");
    test::CliRun r = cli({"render", copy, "--frames", "0-1", "--size", "32x18", "--out", path("deleted_%03d.png")});
    QVERIFY(r.code != 0);
    QVERIFY2(r.err.contains("cut 2 (frames 10-29): camera #21 is not a camera of the scene"), qPrintable(r.err));
    r = cli({"cut", "list", copy});
    QVERIFY(r.out.contains("problem: cut 2"));
  }

  // A stylised transition through the timeline: a swipe without easing is
  // half-way at its middle frame: in each eye the incoming shot on the
  // left, the outgoing one on the right, each as that camera renders it.
  void swipeThroughTheTimeline() {
    const QString swipe = path("swipe.hscene");
    std::string error;
    QVERIFY2(scene::saveScene(twoShots(), swipe.toStdString(), error), error.c_str());
    QVERIFY(cli({"cut", "add", "A", "0f", "9f", swipe}).code == 0);
    test::CliRun r = cli({"cut", "add", "B", "10f", "29f", swipe, "--transition", "swipe", "--duration", "4f",
                          "--ease", "none"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("after a swipe of 4 frames"), qPrintable(r.out));
    QVERIFY(cli({"cut", "list", swipe}).out.contains("swipe of 4 frames"));
    const auto mid = frames("swipe", 12, 12, {}, swipe);
    const auto a = frames("swipe_a", 12, 12, {"--camera", "A"}, swipe);
    const auto b = frames("swipe_b", 12, 12, {"--camera", "B"}, swipe);
    QVERIFY(!mid[0].empty() && a[0] != b[0]);
    // The frames are side by side, two eyes of 64 x 36: the swipe in each eye.
    const size_t width = 128, channels = mid[0].size() / width / 36;
    QVERIFY(channels >= 3 && mid[0].size() == width * 36 * channels);
    int leftOff = 0, rightOff = 0;
    for (size_t y = 0; y < 36; ++y)
      for (size_t x = 0; x < width; ++x)
        for (size_t c = 0; c < 3; ++c) {
          const size_t i = (y * width + x) * channels + c;
          if (x % 64 < 26) leftOff = std::max(leftOff, std::abs(int(mid[0][i]) - int(b[0][i])));
          if (x % 64 >= 38) rightOff = std::max(rightOff, std::abs(int(mid[0][i]) - int(a[0][i])));
        }
    QVERIFY2(leftOff <= 1 && rightOff <= 1, qPrintable(QString("left %1, right %2").arg(leftOff).arg(rightOff)));
    QVERIFY(mid[0] != a[0] && mid[0] != b[0]);
  }

  // A still with --at follows the cuts as the sequence does: cut A's
  // camera inside it, B's after the swipe, the swipe itself in between
  // (the same image as the explicit --mix-camera still); --camera wins.
  void stillAtATimeFollowsTheCuts() {
    const QString swipe = path("swipe.hscene");  // swipeThroughTheTimeline's: A 0-9, a swipe into B 10-29
    auto still = [&](const QString& name, QStringList extra) {
      const test::CliRun r = cli(QStringList{"render", swipe, "--size", "64x36", "--aa", "none", "--out",
                                             path(name)} + extra);
      if (r.code != 0) qWarning("%s", qPrintable(r.err));
      return std::pair{r, pixels(path(name))};
    };
    const auto [r5, at5] = still("at5.png", {"--at", "0.5"});
    const auto a5 = still("a5.png", {"--at", "0.5", "--camera", "A"}).second;
    QVERIFY2(r5.out.contains("camera 'A' (the camera cuts)"), qPrintable(r5.out));
    QVERIFY(!at5.empty() && at5 == a5);
    const auto b20 = still("b20.png", {"--at", "2", "--camera", "B"}).second;
    QVERIFY(still("at20.png", {"--at", "2"}).second == b20);
    const auto [r12, at12] = still("at12.png", {"--at", "1.2"});
    QVERIFY2(r12.out.contains("in a swipe into camera 'B'"), qPrintable(r12.out));
    const auto mixed = still("mix12.png", {"--at", "1.2", "--camera", "A", "--mix-camera", "B", "--mix", "0.5",
                                           "--transition", "swipe"}).second;
    QVERIFY(!at12.empty() && at12 == mixed && at12 != a5);
  }

  // The same as a still: `render --mix-camera B --mix P --transition KIND`.
  void transitionStill() {
    auto still = [&](const QString& name, QStringList extra) {
      const test::CliRun r = cli(QStringList{"render", scene_, "--camera", "A", "--size", "64x36", "--aa", "none",
                                             "--out", path(name)} + extra);
      if (r.code != 0) qWarning("%s", qPrintable(r.err));
      return pixels(path(name));
    };
    const auto fade = still("still_fade.png", {"--mix-camera", "B", "--mix", "0.5"});
    const auto drop = still("still_drop.png", {"--mix-camera", "B", "--mix", "0.5", "--transition", "water_drop"});
    QVERIFY(!fade.empty() && !drop.empty() && fade != drop);
    test::CliRun r = cli({"render", scene_, "--transition", "glitch", "--out", path("no.png")});
    QVERIFY(r.code != 0 && r.err.contains("give --mix-camera too"));
    r = cli({"render", scene_, "--mix-camera", "B", "--transition", "melt", "--out", path("no.png")});
    QVERIFY2(r.code != 0 && r.err.contains("radial_wipe"), qPrintable(r.err));
  }

  void removeRenumbers() {
    test::CliRun r = cli({"cut", "remove", "1", scene_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"cut", "list", scene_});
    QVERIFY2(r.out.contains("cuts: 2") && r.out.contains("1  B"), qPrintable(r.out));
    // B's crossfade lost the shot before it: now a plain cut; A's dip stays.
    QVERIFY(!r.out.contains("crossfade") && r.out.contains("dip_to_black"));
    QVERIFY(cli({"cut", "remove", "5", scene_}).err.contains("no cut 5"));
  }
};

QTEST_GUILESS_MAIN(TestCliCuts)
#include "test_cli_cuts.moc"
