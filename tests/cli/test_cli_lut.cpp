// `lut import|clear` and the LUT in `info`, through the real program
// (tests/common/cli_runner.h): a .cube imported and stored (the render
// still grades after the file is gone), mixed in by `set
// settings.post.lut.intensity`, a refused LUT that leaves the scene as it
// was, and clearing it. `ocio import|list|clear` likewise: a studio config
// with its LUT stored (the folder can go), its displays and views listed
// with the chosen pair, the view transform changing the render, a display
// it lacks refused by `set`, a bad config refused with the scene untouched.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>

#include "cli_runner.h"
#include "file_pixels.h"
#include "file_bytes.h"
#include "lut_files.h"
#include "ocio_files.h"
#include "scene/hscene_file.h"

using namespace hs;

namespace {

std::vector<unsigned char> pixels(const QString& path) { return hs::test::filePixels(path.toStdString()); }

int largestDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  if (a.size() != b.size() || a.empty()) return 1000;
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  return worst;
}

}  // namespace

class TestCliLut : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  QString scene_;

  test::CliRun cli(QStringList args) { return test::runCli(args, tmp_.path()); }
  QString path(const QString& name) const { return tmp_.filePath(name); }
  std::vector<unsigned char> render(const QString& name) {
    const test::CliRun r = cli({"render", scene_, "--frames", "0-0", "--size", "64x36", "--out", path(name + "_%03d.png"),
                                "--aa", "none"});
    if (r.code != 0) qWarning("%s", qPrintable(r.err));
    return pixels(path(name + "_000.png"));
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = path("graded.hscene");
    QCOMPARE(cli({"new", scene_}).code, 0);
  }

  void importStoresAndGrades() {
    const std::vector<unsigned char> plain = render("plain");
    QVERIFY(!plain.empty());
    QVERIFY(test::writeText(path("look.cube").toStdString(), test::cube3dText(17, test::tealOrangeLook)));
    test::CliRun r = cli({"lut", "import", path("look.cube"), scene_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("graded") && r.out.contains("look.cube"));
    QFile::remove(path("look.cube"));  // the scene holds it
    r = cli({"info", scene_});
    QVERIFY(r.out.contains("LUT: look.cube"));
    QVERIFY(r.out.contains("on, intensity 1"));
    r = cli({"info", scene_, "--json"});
    QVERIFY(r.out.contains("\"post.lut\""));
    const std::vector<unsigned char> graded = render("graded");
    QVERIFY(largestDifference(graded, plain) > 10);
    // Mixed in at half: between the two.
    r = cli({"set", "settings.post.lut.intensity", "0.5", scene_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const std::vector<unsigned char> half = render("half");
    QVERIFY(largestDifference(half, plain) > 3 && largestDifference(half, graded) > 3);
    const std::string before = test::readFile(scene_.toStdString());
    r = cli({"set", "settings.post.lut.intensity", "2", scene_});  // refused by its range, the file untouched
    QVERIFY2(r.code != 0 && r.err.contains("LUT intensity must be from 0 to 1"), qPrintable(r.err));
    QVERIFY(test::readFile(scene_.toStdString()) == before);
  }

  void aRefusedLutLeavesTheScene() {
    const std::string before = test::readFile(scene_.toStdString());
    std::string text = test::cube3dText(4, test::identityLook);
    text.replace(text.find("0.333333 0.000000 0.000000"), 8, "nan");
    QVERIFY(test::writeText(path("bad.cube").toStdString(), text));
    test::CliRun r = cli({"lut", "import", path("bad.cube"), scene_});
    QVERIFY(r.code != 0);
    QVERIFY2(r.err.contains("bad.cube:5: 'nan' is not a finite number"), qPrintable(r.err));
    QVERIFY(test::readFile(scene_.toStdString()) == before);
    r = cli({"lut", "import", path("absent.cube"), scene_});
    QVERIFY(r.code != 0 && r.err.contains("absent.cube"));
    QVERIFY(test::readFile(scene_.toStdString()) == before);
    r = cli({"lut", "import", scene_});
    QCOMPARE(r.code, 2);  // usage
  }

  void clearRemovesIt() {
    test::CliRun r = cli({"lut", "clear", scene_});
    QVERIFY2(r.code == 0 && r.out.contains("removed"), qPrintable(r.err));
    QVERIFY(!cli({"info", scene_}).out.contains("LUT:"));
    r = cli({"lut", "clear", scene_});
    QVERIFY(r.code == 0 && r.out.contains("unchanged"));
  }

  void ocioImportListsAndViews() {
    const QString scene = path("viewed.hscene");
    QCOMPARE(cli({"new", scene}).code, 0);
    scene_ = scene;
    const std::vector<unsigned char> plain = render("untransformed");
    const std::filesystem::path studio = std::filesystem::path(tmp_.path().toStdString()) / "studio";
    const std::string config = test::writeStudioConfig(studio);
    test::CliRun r = cli({"ocio", "import", QString::fromStdString(config), scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("'studio.ocio' (2 files") && r.out.contains("display 'Studio sRGB', view 'Film'"),
             qPrintable(r.out));
    std::filesystem::remove_all(studio);  // the scene holds it
    r = cli({"ocio", "list", scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("enters as 'scene_linear'; view transform on"), qPrintable(r.out));
    QVERIFY(r.out.contains("display 'Studio sRGB' (default)") && r.out.contains("display 'Projector'"));
    QVERIFY(r.out.contains("view 'Film' (default)  <- chosen") && r.out.contains("search0/film.spi1d"));
    r = cli({"info", scene});
    QVERIFY2(r.out.contains("OpenColorIO config: studio.ocio (2 files, stored in the scene), view transform on"),
             qPrintable(r.out));
    QVERIFY(largestDifference(render("film"), plain) > 10);
    // A display the config lacks: refused with what it has, the file untouched.
    const std::string before = test::readFile(scene.toStdString());
    r = cli({"set", "settings.post.view_transform.display", "Cinema", scene});
    QVERIFY2(r.code != 0 && r.err.contains("no display 'Cinema' (it has 'Studio sRGB', 'Projector')"),
             qPrintable(r.err));
    QVERIFY(test::readFile(scene.toStdString()) == before);
    // A camera's override too (its field alone knows no config).
    r = cli({"set", "Camera", "camera.post.view_transform.view", "Nope", scene});
    QVERIFY2(r.code != 0 && r.err.contains("has no view 'Nope' (it has 'Film', 'Raw')"), qPrintable(r.err));
    QVERIFY(test::readFile(scene.toStdString()) == before);
    r = cli({"set", "settings.post.view_transform.view", "Raw", scene});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(cli({"ocio", "list", scene}).out.contains("view 'Raw'  <- chosen"));
    // A bad config leaves the scene as it was.
    const std::string kept = test::readFile(scene.toStdString());
    QVERIFY(test::writeText(path("broken.ocio").toStdString(), "ocio_profile_version: 2\nroles: [unclosed\n"));
    r = cli({"ocio", "import", path("broken.ocio"), scene});
    QVERIFY2(r.code != 0 && r.err.contains("broken.ocio: OpenColorIO cannot read it"), qPrintable(r.err));
    QVERIFY(test::readFile(scene.toStdString()) == kept);
    r = cli({"ocio", "clear", scene});
    QVERIFY2(r.code == 0 && r.out.contains("removed"), qPrintable(r.err));
    QVERIFY(!cli({"info", scene}).out.contains("OpenColorIO config:"));
    QVERIFY(cli({"ocio", "list", scene}).out.contains("stores no OpenColorIO config"));
  }
};

QTEST_GUILESS_MAIN(TestCliLut)
#include "test_cli_lut.moc"
