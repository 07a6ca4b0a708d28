// Every shared operation's options, driven through the real hybridscape-cli
// at the bounds its declaration gives (scene/operation_registry.h): each
// number at its minimum and maximum is accepted, and just outside (the next
// double, or the next whole number) is refused with exit 2 and one line
// naming the option; each choice is accepted and a name that is not one is
// refused. The editor's widgets are checked against the same declarations
// (tests/app/test_editor_params.cpp), so the two frontends cannot drift.
//
// How "accepted" is seen without running the work: every command checks
// its options before it opens the scene, and the scene named here does not
// exist, so an accepted value ends in exit 1 naming the missing scene
// (`farm verify`, which opens no scene, in exit 1 for the missing frames).
#include <QDir>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <map>
#include <memory>

#include "cli_runner.h"
#include "scene/operation_registry.h"

using namespace hs;

namespace {

const QString kMesh = HS_TEST_DATA_DIR "/mesh/textured_quad.obj";
const QString kDem = HS_TEST_DATA_DIR "/terrain/dem_wgs84.tif";

// A number as the command line takes it: whole numbers plainly, others
// with every digit a double needs.
QString numberText(double v, bool integer) {
  if (integer) return QString::number(static_cast<long long>(v));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The smallest step past `v` towards `direction` for this parameter.
double beyond(const ParamDecl& p, double v, double direction) {
  return p.integer ? v + direction : std::nextafter(v, direction * double(INFINITY));
}

QString tupleText(const ParamDecl& p, const std::vector<double>& v) {
  QStringList parts;
  for (double x : v) parts << numberText(x, p.integer);
  return parts.join(QChar(p.separator));
}

// Values the declaration accepts at its bounds: for a scalar its minimum
// and maximum; for a tuple every number at its minimum, and every number
// at its maximum (an ordered tuple: the first at its minimum, the rest at
// their maximum, so both bounds are met in one value).
std::vector<std::vector<double>> boundValues(const ParamDecl& p) {
  std::vector<double> lo, hi, span;
  for (int i = 0; i < p.count; ++i) {
    lo.push_back(componentMin(p, i));
    hi.push_back(componentMax(p, i));
    span.push_back(i == 0 ? componentMin(p, i) : componentMax(p, i));
  }
  if (p.ordered) return {span};
  return {lo, hi};
}

struct Probe {
  QString text;
  bool accepted;
};

// Runs every command line at once (each run spends most of its time
// loading libraries) and returns the runs in the same order.
std::vector<test::CliRun> runAll(const std::vector<QStringList>& commands, const QString& workDir) {
  std::vector<std::unique_ptr<QProcess>> procs;
  for (const QStringList& args : commands) {
    procs.push_back(std::make_unique<QProcess>());
    procs.back()->setWorkingDirectory(workDir);
    procs.back()->start(test::kCli, args);
  }
  std::vector<test::CliRun> runs(commands.size());
  for (size_t i = 0; i < procs.size(); ++i) {
    QProcess& p = *procs[i];
    if (!p.waitForFinished(120000)) {
      p.kill();
      p.waitForFinished();
      continue;  // code -1: the test reports it
    }
    runs[i].code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
    runs[i].out = QString::fromLocal8Bit(p.readAllStandardOutput());
    runs[i].err = QString::fromLocal8Bit(p.readAllStandardError());
  }
  return runs;
}

std::vector<Probe> probes(const ParamDecl& p) {
  std::vector<Probe> out;
  if (p.type == ParamType::Choice) {
    for (const std::string& c : p.choices) out.push_back({QString::fromStdString(c.substr(0, c.find('|'))), true});
    out.push_back({"no-such-choice", false});
    return out;
  }
  const std::vector<std::vector<double>> bounds = boundValues(p);
  for (const auto& v : bounds) out.push_back({tupleText(p, v), true});
  // Each number just outside its range, the others at accepted bounds.
  for (int i = 0; i < p.count; ++i) {
    std::vector<double> below = bounds.front(), above = bounds.back();
    below[size_t(i)] = beyond(p, componentMin(p, i), -1.0);
    above[size_t(i)] = beyond(p, componentMax(p, i), +1.0);
    out.push_back({tupleText(p, below), false});
    out.push_back({tupleText(p, above), false});
  }
  return out;
}

}  // namespace

class TestCliParams : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString missing_;  // a scene that does not exist

  // The command line of each operation before the option under test, and
  // what its stderr says when the run got past the options.
  struct Base {
    QStringList args;
    QString marker;
  };
  std::map<std::string, Base> bases() const {
    const QString frames = tmp_.filePath("none/f_%03d.png");
    return {
        {"import", {{"import", kMesh, missing_}, missing_}},
        {"mesh export", {{"mesh", "export", missing_, "Bunny", tmp_.filePath("bunny.obj")}, missing_}},
        {"terrain new", {{"terrain", "new", missing_, "--size", "100", "--resolution", "65"}, missing_}},
        {"terrain import", {{"terrain", "import", kDem, missing_}, missing_}},
        {"terrain erode", {{"terrain", "erode", missing_, "--thermal"}, missing_}},
        {"terrain paint-rules", {{"terrain", "paint-rules", missing_}, missing_}},
        {"terrain layer", {{"terrain", "layer", missing_, "--layer", "0"}, missing_}},
        {"terrain export", {{"terrain", "export", missing_, "--out", tmp_.filePath("h.png")}, missing_}},
        {"render", {{"render", missing_, "--out", frames}, missing_}},
        {"sequence", {{"sequence", missing_}, missing_}},
        {"key", {{"key", "Camera", "camera.fov_deg", "0", "50", missing_}, missing_}},
        {"path", {{"path", "Camera", missing_}, missing_}},
        {"farm slurm", {{"farm", "slurm", missing_, "--out", frames}, missing_}},
        {"farm verify", {{"farm", "verify", "--frames", "0-1", "--out", frames}, "frame(s) missing"}},
        {"repair", {{"repair", missing_, tmp_.filePath("repaired.hscene")}, missing_}},
        {"light add", {{"light", "add", missing_, "--type", "spot"}, missing_}},
        {"foliage type add", {{"foliage", "type", "add", "T", "--mesh", "M", missing_}, missing_}},
        {"foliage scatter", {{"foliage", "scatter", "T", missing_}, missing_}},
        {"foliage fill", {{"foliage", "fill", "T", missing_, "--layer", "Grass"}, missing_}},
        {"foliage clear", {{"foliage", "clear", "T", missing_}, missing_}},
        {"foliage plant", {{"foliage", "plant", "P", "--kind", "rock", missing_}, missing_}},
        {"foliage move", {{"foliage", "move", "T", missing_, "--offset", "1,2,0"}, missing_}},
        {"foliage impostors", {{"foliage", "impostors", missing_}, missing_}},
        {"particles add", {{"particles", "add", "snow", missing_}, missing_}},
    };
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(test::kCli).isExecutable(), qPrintable(test::kCli + " is not built"));
    missing_ = tmp_.filePath("missing.hscene");
  }

  // A new operation in the registry needs a command line here.
  void everyOperationIsDriven() {
    const auto b = bases();
    for (const OperationDecl* op : scene::sharedOperations())
      QVERIFY2(b.count(op->name), qPrintable(QString::fromStdString(op->name) + " has no command line in this test"));
  }

  void boundsOfEveryOption_data() {
    QTest::addColumn<QString>("operation");
    QTest::addColumn<QString>("key");
    int rows = 0;
    for (const OperationDecl* op : scene::sharedOperations())
      for (const ParamDecl& p : op->params) {
        if (p.option.empty() || (p.type != ParamType::Number && p.type != ParamType::Choice)) continue;
        QTest::newRow((op->name + " --" + p.option).c_str())
            << QString::fromStdString(op->name) << QString::fromStdString(p.key);
        ++rows;
      }
    QVERIFY(rows > 30);  // the registry is not empty by mistake
  }

  void boundsOfEveryOption() {
    QFETCH(QString, operation);
    QFETCH(QString, key);
    const OperationDecl* op = scene::findOperation(operation.toStdString());
    QVERIFY(op);
    const ParamDecl& p = op->param(key.toStdString());
    const Base base = bases().at(op->name);
    const QString option = "--" + QString::fromStdString(p.option);
    const std::vector<Probe> all = probes(p);
    std::vector<QStringList> commands;
    for (const Probe& probe : all) commands.push_back(base.args + QStringList{option, probe.text});
    const std::vector<test::CliRun> runs = runAll(commands, tmp_.path());
    for (size_t i = 0; i < all.size(); ++i) {
      const Probe& probe = all[i];
      const test::CliRun& r = runs[i];
      const QString cmd = "hybridscape-cli " + commands[i].join(' ');
      if (probe.accepted) {
        QVERIFY2(r.code == 1 && r.err.contains(base.marker),
                 qPrintable(QString("%1: accepted value should reach the scene (exit 1, '%2'); exit %3: %4")
                                .arg(cmd, base.marker)
                                .arg(r.code)
                                .arg(r.err)));
      } else {
        QVERIFY2(r.code == 2, qPrintable(QString("%1: exit %2, expected 2: %3").arg(cmd).arg(r.code).arg(r.err)));
        QVERIFY2(r.errLines().size() == 1 && r.err.contains(option),
                 qPrintable(QString("%1: expected one line naming %2, got: %3").arg(cmd, option, r.err)));
      }
    }
  }

  // The help of each operation shows each option with its range, the way
  // the declaration states it.
  void helpShowsTheDeclaredRanges() {
    for (const OperationDecl* op : scene::sharedOperations()) {
      QStringList args = QString::fromStdString(op->name).split(' ');
      args << "--help";
      const test::CliRun r = test::runCli(args, tmp_.path());
      QCOMPARE(r.code, 0);
      QString flat = r.out.simplified();
      for (const ParamDecl& p : op->params) {
        if (p.option.empty()) continue;
        QVERIFY2(r.out.contains("--" + QString::fromStdString(p.option)),
                 qPrintable(QString::fromStdString(op->name + ": --" + p.option + " not in its help")));
        if (p.type == ParamType::Number)
          QVERIFY2(flat.contains(QString::fromStdString(rangeText(p)).simplified()),
                   qPrintable(QString::fromStdString(op->name + ": the range of --" + p.option + " (" +
                                                     rangeText(p) + ") not in its help")));
      }
    }
  }
};

QTEST_GUILESS_MAIN(TestCliParams)
#include "test_cli_params.moc"
