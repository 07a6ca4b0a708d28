// Interruption tests (issue 10 item 7; docs/reliability.md): the real
// hybridscape-cli is killed with SIGKILL at random moments (a fixed seed)
// while it imports a mesh and saves, erodes a terrain and saves, and
// exports a frame sequence. After each kill the scene opens and holds
// either the state before the command or the state a clean run of it
// leaves, exactly (canonical description, every blob checked against its
// hash by the loader); a resumed export equals a clean run byte for byte.
#include <QElapsedTimer>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <fstream>
#include <random>

#include "cli_runner.h"
#include "core/json.h"
#include "file_bytes.h"
#include "scene/hscene_file.h"
#include "scene/scene_json.h"

using namespace hs;
using hs::test::kCli;
namespace fs = std::filesystem;

namespace {

// Removes members named "seconds" at any depth: the import report's run
// time, the one value a second run of the same command does not repeat.
void dropRunTimes(Json& j) {
  if (j.is_object()) {
    j.erase("seconds");
    for (auto& [key, value] : j.items()) dropRunTimes(value);
  } else if (j.is_array()) {
    for (Json& value : j) dropRunTimes(value);
  }
}

// The scene as the loader reads it: canonical description (assets carry
// their content hashes, which the loader checks every blob against) less
// run times, or the error that kept it from opening.
std::string stateOf(const std::string& path) {
  std::string error;
  const auto s = scene::loadScene(path, error);
  if (!s) return "cannot open: " + error;
  std::optional<Json> j = parseJson(scene::canonicalJson(*s), error);
  if (!j) return "canonical JSON does not parse: " + error;
  dropRunTimes(*j);
  return writeJson(*j, -1);
}

// A flat grid of n x n quads as OBJ: a mesh whose import and save take long
// enough (about a second) for kills to land in every stage.
void writeGridObj(const std::string& path, int n) {
  std::ofstream f(path);
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) f << "v " << x << ' ' << y << ' ' << ((x * 7 + y * 3) % 11) * 0.1 << '\n';
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
      f << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
    }
}

}  // namespace

class TestCliInterrupt : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  std::mt19937 rng_{10};  // fixed: the same kill moments every run

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }

  test::CliRun cli(const QStringList& args) { return test::runCli(args, tmp_.path(), 120000); }

  // Starts `args`, kills it after `ms` unless it finished; true if killed.
  // With `startsAt`, the `ms` count from when that file appears (a save's
  // journal: the kill then lands inside the save).
  bool runAndKill(const QStringList& args, int ms, const std::string& startsAt = {}) {
    QProcess p;
    p.setWorkingDirectory(tmp_.path());
    p.start(kCli, args);
    if (!p.waitForStarted()) return false;
    if (!startsAt.empty())
      while (!fs::exists(startsAt))
        if (p.waitForFinished(1)) return false;
    if (p.waitForFinished(ms)) return false;
    p.kill();  // SIGKILL: no handler runs
    p.waitForFinished();
    return true;
  }

  // Runs `command` (with the scene path at %1) on copies of `base`, killed
  // `kills` times at random moments within a clean run's time; each time
  // the scene must hold the state before or the state after.
  void killDuring(const QString& what, const std::string& base, const QStringList& command, int kills) {
    const std::string before = stateOf(base);
    QVERIFY2(before.rfind("cannot open", 0) != 0, before.c_str());
    const std::string clean = path("clean.hscene");
    fs::copy_file(base, clean, fs::copy_options::overwrite_existing);
    QStringList args = command;
    args.replaceInStrings("%1", QString::fromStdString(clean));
    QElapsedTimer t;
    t.start();
    const test::CliRun r = cli(args);
    const int cleanMs = int(t.elapsed());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const std::string after = stateOf(clean);
    QVERIFY(after != before);
    int sawBefore = 0, sawAfter = 0, finished = 0;
    // Half the kills anywhere in a clean run's time; half inside the save:
    // 0-100 ms after its journal appears (some runs then finish first).
    std::uniform_int_distribution<int> anywhere(10, std::max(20, cleanMs));
    std::uniform_int_distribution<int> inSave(0, 100);
    QString moments;
    int midSave = 0;
    for (int k = 0; k < kills; ++k) {
      const std::string victim = path("killed.hscene");
      fs::remove(victim);
      fs::remove(victim + "-journal");
      fs::copy_file(base, victim);
      args = command;
      args.replaceInStrings("%1", QString::fromStdString(victim));
      const bool save = k % 2;
      const int ms = save ? inSave(rng_) : anywhere(rng_);
      const bool killed = runAndKill(args, ms, save ? victim + "-journal" : std::string());
      finished += !killed;
      const bool journal = fs::exists(victim + "-journal");  // a save was under way
      midSave += killed && journal;
      const std::string now = stateOf(victim);
      QVERIFY2(now == before || now == after,
               qPrintable(QString("%1 killed at %2 ms: the scene holds neither state: %3")
                              .arg(what)
                              .arg(ms)
                              .arg(QString::fromStdString(now.substr(0, 300)))));
      ++(now == before ? sawBefore : sawAfter);
      moments += QString(" %1%2%3").arg(save ? "save+" : "").arg(ms).arg(
          killed ? (now == before ? "(old)" : "(new)") : "(done)");
    }
    qInfo("%s: clean run %d ms; %d kills: %d left the old state, %d the new (%d finished before the kill, %d killed "
          "mid-save with a hot journal); at ms:%s",
          qPrintable(what), cleanMs, kills, sawBefore, sawAfter, finished, midSave, qPrintable(moments));
    QVERIFY(midSave > 0);  // the kills did reach the save
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
  }

  void importAndSave() {
    const std::string base = path("import-base.hscene");
    QCOMPARE(cli({"new", QString::fromStdString(base)}).code, 0);
    const std::string grid = path("grid.obj");
    writeGridObj(grid, 600);  // 720,000 triangles
    killDuring("import", base, {"import", QString::fromStdString(grid), "%1"}, 8);
  }

  void terrainErosionAndSave() {
    const std::string base = path("terrain-base.hscene");
    QCOMPARE(cli({"new", QString::fromStdString(base)}).code, 0);
    const test::CliRun r = cli({"terrain", "new", QString::fromStdString(base), "--size", "500", "--resolution", "513",
                                  "--height", "0,120", "--hills"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    killDuring("terrain erode", base, {"terrain", "erode", "%1", "--thermal", "--iterations", "40"}, 8);
  }

  void sequenceExportResumes() {
    const std::string scene = path("demo.hscene");
    QCOMPARE(cli({"demo", QString::fromStdString(scene)}).code, 0);
    auto render = [&](const std::string& dir) {
      return QStringList{"render", QString::fromStdString(scene), "--frames", "0-7", "--size", "128x72", "--aa", "none",
                         "--out", QString::fromStdString(dir) + "/f_%03d.png"};
    };
    const std::string clean = path("frames-clean");
    QElapsedTimer t;
    t.start();
    test::CliRun r = cli(render(clean));
    const int cleanMs = int(t.elapsed());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    std::uniform_int_distribution<int> moment(10, std::max(20, cleanMs));
    int killed = 0;
    for (int k = 0; k < 3; ++k) {
      const std::string dir = path("frames-killed-" + std::to_string(k));
      // Killed twice at random moments, then resumed to the end.
      for (int again = 0; again < 2; ++again) killed += runAndKill(render(dir), moment(rng_));
      r = cli(render(dir));
      QVERIFY2(r.code == 0, qPrintable(r.err));
      for (int f = 0; f < 8; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "/f_%03d.png", f);
        QVERIFY2(test::readFile(dir + name) == test::readFile(clean + name),
                 qPrintable(QString("run %1: frame %2 differs from the clean run after resuming").arg(k).arg(f)));
      }
      int files = 0;
      for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
      QCOMPARE(files, 8);  // no temporary left beside the frames
    }
    qInfo("export: clean run %d ms; %d of 6 runs killed, all 3 resumed equal to the clean run", cleanMs, killed);
  }
};

QTEST_GUILESS_MAIN(TestCliInterrupt)
#include "test_cli_interrupt.moc"
