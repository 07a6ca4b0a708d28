// A render-farm run on a real Slurm: tests/sequencer/slurm_local.sh starts a
// one-node Slurm with munge on localhost, `hybridscape-cli farm slurm
// --submit` submits the job array and its dependent check, the test waits
// for both, and the farm's frames must be byte-identical to a single-machine
// `hybridscape-cli render` of the same range. The daemons are stopped and
// the jobs cancelled whatever happens (a guard object; QtTest runs
// cleanupTestCase after failures too). Needs root (CI runs as root on a
// fresh machine) and Debian's slurm-wlm and munge (scripts/deps.sh --with-tests).
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <unistd.h>

#include "file_bytes.h"

namespace fs = std::filesystem;

namespace {

const QString kCli = HS_BINARY_DIR "/cli/hybridscape-cli";
const QString kSlurm = HS_SOURCE_DIR "/tests/sequencer/slurm_local.sh";

struct Run {
  int code = -1;
  QString out;
};

Run run(const QString& program, const QStringList& args, int timeoutMs = 120000) {
  QProcess p;
  p.setProcessChannelMode(QProcess::MergedChannels);
  p.start(program, args);
  Run r;
  if (!p.waitForFinished(timeoutMs)) {
    p.kill();
    p.waitForFinished();
    r.out = "timed out: " + program + " " + args.join(' ');
    return r;
  }
  r.code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
  r.out = QString::fromLocal8Bit(p.readAll());
  return r;
}

// "JobState=COMPLETED" of a job, or "" once Slurm has forgotten it.
QString jobState(const QString& id) {
  const Run r = run("scontrol", {"show", "job", id, "-o"}, 10000);
  const QRegularExpressionMatch m = QRegularExpression("JobState=(\\S+)").match(r.out);
  return m.hasMatch() ? m.captured(1) : QString();
}

bool terminal(const QString& state) {
  return state == "COMPLETED" || state == "FAILED" || state == "CANCELLED" || state == "TIMEOUT" ||
         state == "NODE_FAIL" || state == "OUT_OF_MEMORY" || state == "PREEMPTED";
}

}  // namespace

class TestFarmSlurm : public QObject {
  Q_OBJECT

  // Stops what the test started, also when a check fails or throws.
  struct SlurmGuard {
    bool started = false;
    QStringList jobs;
    ~SlurmGuard() { stop(); }
    void stop() {
      if (!jobs.isEmpty()) run("scancel", jobs, 20000);
      jobs.clear();
      if (started) {
        const Run r = run("bash", {kSlurm, "stop"}, 60000);
        qInfo("slurm_local.sh stop: %s", qPrintable(r.out.trimmed()));
      }
      started = false;
    }
  };

  QTemporaryDir tmp_;
  SlurmGuard slurm_;

 private slots:
  void initTestCase() {
    if (::geteuid() != 0) QSKIP("the Slurm test starts daemons as root (CI runs as root)");
    if (QStandardPaths::findExecutable("slurmctld", {"/usr/sbin", "/usr/bin"}).isEmpty() ||
        QStandardPaths::findExecutable("munged", {"/usr/sbin", "/usr/bin"}).isEmpty())
      QSKIP("slurm-wlm and munge are not installed (scripts/deps.sh --with-tests)");
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
    slurm_.started = true;  // stop even if start fails half-way
    const Run r = run("bash", {kSlurm, "start"}, 90000);
    QVERIFY2(r.code == 0, qPrintable("slurm_local.sh start failed:\n" + r.out));
  }

  void farmRunMatchesASingleMachine() {
    const QString scene = tmp_.filePath("valley.hscene");
    Run r = run(kCli, {"demo", scene});
    QVERIFY2(r.code == 0, qPrintable(r.out));
    const QString work = tmp_.filePath("job");
    const QString frames = work + "/frames/f_%03d.png";
    // 24 frames in 4 array tasks of 6; small frames without MSAA keep it quick.
    QElapsedTimer clock;
    clock.start();
    r = run(kCli, {"farm", "slurm", scene, "--frames", "0-23", "--chunk", "6", "--layout", "sbs", "--size", "64x36",
                   "--aa", "none", "--out", frames, "--dir", work, "--mem", "1G", "--time", "00:10:00", "--submit"});
    QVERIFY2(r.code == 0, qPrintable(r.out));
    qInfo("%s", qPrintable(r.out.trimmed()));
    const QRegularExpressionMatch m = QRegularExpression("render array: job (\\d+) \\(4 tasks\\); check: job (\\d+)").match(r.out);
    QVERIFY2(m.hasMatch(), qPrintable(r.out));
    const QString array = m.captured(1), check = m.captured(2);
    slurm_.jobs = {array, check};

    QString state;
    while (clock.elapsed() < 150000) {
      state = jobState(check);
      if (terminal(state)) break;
      QTest::qWait(500);
    }
    qInfo("array job %s and check job %s ended in %.1f s (check: %s)", qPrintable(array), qPrintable(check),
          clock.elapsed() / 1000.0, qPrintable(state));
    const QString checkLog = work + "/slurm-logs/hybridscape-verify_" + check + ".out";
    const QString log = QString::fromStdString(hs::test::readFile(checkLog.toStdString()));
    QVERIFY2(state == "COMPLETED", qPrintable(QString("check job %1: %2\n%3").arg(check, state, log)));
    QVERIFY2(log.contains("24 of 24 frames valid"), qPrintable(log));
    for (int task = 0; task < 4; ++task) {
      const QString taskLog = QString::fromStdString(hs::test::readFile(
          QString("%1/slurm-logs/hybridscape-render_%2_%3.out").arg(work, array).arg(task).toStdString()));
      QVERIFY2(taskLog.contains("rendered 6 frame(s), kept 0, of 6"), qPrintable(taskLog));
    }
    slurm_.jobs.clear();

    // The same range on this machine, in one run.
    const QString single = tmp_.filePath("single");
    r = run(kCli, {"render", scene, "--frames", "0-23", "--layout", "sbs", "--size", "64x36", "--aa", "none", "--out",
                   single + "/f_%03d.png"});
    QVERIFY2(r.code == 0, qPrintable(r.out));
    for (int f = 0; f < 24; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "/f_%03d.png", f);
      const std::string a = hs::test::readFile((work + "/frames").toStdString() + name);
      const std::string b = hs::test::readFile(single.toStdString() + name);
      QVERIFY2(!a.empty() && a == b, qPrintable(QString("frame %1 differs between the farm and one machine").arg(f)));
    }
  }

  void cleanupTestCase() { slurm_.stop(); }
};

QTEST_GUILESS_MAIN(TestFarmSlurm)
#include "test_farm_slurm.moc"
