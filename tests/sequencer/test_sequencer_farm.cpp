// Render-farm scripts: the job array's shape and command lines, quoting,
// and a whole farm run acted out with bash (every array task, then the
// check) using hs_sequencer_tool as the CLI. The real Slurm run is
// tests/sequencer/slurm_local.sh (phase 2 turns it into a test).
#include <QtTest>

#include <filesystem>

#include "sequencer/slurm_script.h"

using namespace hs::sequencer;
namespace fs = std::filesystem;

namespace {

FarmJob filmJob() {
  FarmJob job;
  std::string error;
  job.scenePath = "/farm/meteora valley's.hscene";
  job.frames = *FrameList::parse("0-35999", error);
  job.chunkSize = 600;
  job.outputPattern = "frames/f_%05d.png";
  job.workDir = "/farm/films/meteora";
  return job;
}

QString runBash(const QString& script, const QStringList& env, const QString& cwd, int& exitCode) {
  QProcess p;
  p.setProcessChannelMode(QProcess::MergedChannels);
  QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
  for (const QString& kv : env) e.insert(kv.section('=', 0, 0), kv.section('=', 1));
  p.setProcessEnvironment(e);
  p.setWorkingDirectory(cwd);
  p.start("bash", {script});
  p.waitForFinished(60000);
  exitCode = p.exitCode();
  return QString::fromUtf8(p.readAll());
}

}  // namespace

class TestFarm : public QObject {
  Q_OBJECT

 private slots:
  void scriptShape() {
    std::string error;
    const FarmScripts s = makeSlurmScripts(filmJob(), error);
    QVERIFY2(error.empty(), error.c_str());
    QCOMPARE(s.chunks.size(), size_t(60));
    QVERIFY(s.warnings.empty());
    const std::string& r = s.renderScript;
    QVERIFY(r.rfind("#!/bin/bash\n", 0) == 0);
    QVERIFY(r.find("#SBATCH --array=0-59\n") != std::string::npos);
    QVERIFY(r.find("#SBATCH --chdir=/farm/films/meteora\n") != std::string::npos);
    QVERIFY(r.find("#SBATCH --output=slurm-logs/%x_%A_%a.out\n") != std::string::npos);
    QVERIFY(r.find("#SBATCH --requeue\n") != std::string::npos);
    QVERIFY(r.find("  0-599\n") != std::string::npos);
    QVERIFY(r.find("  35400-35999\n") != std::string::npos);
    QVERIFY(r.find("frames=${CHUNKS[$SLURM_ARRAY_TASK_ID]}") != std::string::npos);
    QVERIFY2(r.find("exec hybridscape-cli render '/farm/meteora valley'\\''s.hscene' --frames \"$frames\" --layout sbs "
                    "--size 1920x1080 --out 'frames/f_%05d.png'\n") != std::string::npos,
             r.c_str());
    QVERIFY(s.verifyScript.find("exec hybridscape-cli farm verify --frames 0-35999 --layout sbs --size 1920x1080 "
                                "--out 'frames/f_%05d.png' --chunk 600\n") != std::string::npos);
    QVERIFY(s.submitScript.find("--dependency=afterany:$render") != std::string::npos);
    QVERIFY(s.submitScript.find("mkdir -p /farm/films/meteora/slurm-logs") != std::string::npos);
    qInfo("render.sbatch (chunk list shortened):\n%s", (r.substr(0, r.find("  1200-1799")) + "  ...\n" + r.substr(r.find(")\nframes="))).c_str());
    // Options.
    FarmJob job = filmJob();
    job.maxConcurrent = 8;
    job.partition = "gpu";
    job.sbatchLines = {"--gres=gpu:1"};
    job.renderArgs = {"--camera", "Drone 1"};
    const FarmScripts o = makeSlurmScripts(job, error);
    QVERIFY(o.renderScript.find("#SBATCH --array=0-59%8\n") != std::string::npos);
    QVERIFY(o.renderScript.find("#SBATCH --partition=gpu\n") != std::string::npos);
    QVERIFY(o.renderScript.find("#SBATCH --gres=gpu:1\n") != std::string::npos);
    QVERIFY(o.renderScript.find("--camera 'Drone 1'\n") != std::string::npos);
  }

  void chunksFollowTheFrameList() {
    FarmJob job = filmJob();
    std::string error;
    job.frames = *FrameList::parse("10,20-30,100-200x50", error);
    job.chunkSize = 5;
    const FarmScripts s = makeSlurmScripts(job, error);
    QCOMPARE(s.chunks.size(), size_t(3));
    QVERIFY(s.renderScript.find("  10,20-23\n") != std::string::npos);
    QVERIFY(s.renderScript.find("  29-30,100-200x50\n") != std::string::npos);
    // Too many tasks for Slurm's default MaxArraySize: a warning with a fix.
    job.frames = FrameList::range(0, 35999);
    job.chunkSize = 10;
    const FarmScripts many = makeSlurmScripts(job, error);
    QCOMPARE(many.warnings.size(), size_t(1));
    QVERIFY(many.warnings[0].find("--chunk 36") != std::string::npos);
    job.chunkSize = 0;
    QVERIFY(makeSlurmScripts(job, error).renderScript.empty());
    QVERIFY(!error.empty());
  }

  void shellQuoting() {
    QCOMPARE(shellQuote("plain/path-1.png"), std::string("plain/path-1.png"));
    QCOMPARE(shellQuote("a b"), std::string("'a b'"));
    QCOMPARE(shellQuote("it's"), std::string("'it'\\''s'"));
    QCOMPARE(shellQuote("f_%05d.png"), std::string("'f_%05d.png'"));
    QCOMPARE(shellQuote("$HOME"), std::string("'$HOME'"));
    QCOMPARE(shellQuote(""), std::string("''"));
  }

  void scriptsAreValidBash() {
    std::string error;
    const FarmScripts s = makeSlurmScripts(filmJob(), error);
    QTemporaryDir tmp;
    QVERIFY(writeSlurmScripts(s, tmp.path().toStdString(), error));
    for (const char* name : {"render.sbatch", "verify.sbatch", "submit.sh"}) {
      QProcess p;
      p.start("bash", {"-n", tmp.path() + "/" + name});
      QVERIFY(p.waitForFinished());
      QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
    }
    QVERIFY(fs::status((tmp.path() + "/submit.sh").toStdString()).permissions() & fs::perms::owner_exec);
  }

  void farmRunActedOutWithBash() {
    // Every array task as Slurm would start it (SLURM_ARRAY_TASK_ID), then
    // the final check, with the phase-1 stand-in CLI.
    QTemporaryDir tmp;
    const std::string work = tmp.path().toStdString() + "/work dir";
    fs::create_directories(work + "/frames");
    FarmJob job;
    std::string error;
    job.scenePath = "demo.hscene";
    job.frames = *FrameList::parse("0-47", error);
    job.chunkSize = 10;
    job.eyeWidth = 32;
    job.eyeHeight = 18;
    job.workDir = work;
    job.cli = std::string(HS_BINARY_DIR) + "/tests/sequencer/hs_sequencer_tool";
    const FarmScripts s = makeSlurmScripts(job, error);
    QVERIFY(writeSlurmScripts(s, work, error));
    int code = 0;
    for (size_t task = 0; task < s.chunks.size(); ++task) {
      const QString out = runBash(QString::fromStdString(work + "/render.sbatch"),
                                  {QString("SLURM_ARRAY_TASK_ID=%1").arg(task), "SLURM_ARRAY_JOB_ID=1"}, "/", code);
      QVERIFY2(code == 0, qPrintable(out));
    }
    QString out = runBash(QString::fromStdString(work + "/verify.sbatch"), {}, "/", code);
    QVERIFY2(code == 0, qPrintable(out));
    QVERIFY(out.contains("48 of 48 frames valid"));
    // A lost frame: the check fails and names the chunk to run again.
    fs::remove(work + "/frames/f_00025.png");
    out = runBash(QString::fromStdString(work + "/verify.sbatch"), {}, "/", code);
    QCOMPARE(code, 1);
    qInfo("%s", qPrintable(out.trimmed()));
    QVERIFY(out.contains("missing frames: 25"));
    QVERIFY(out.contains("chunks (job-array tasks) to run again: 2"));
    // Running that task again (a requeue) repairs it.
    out = runBash(QString::fromStdString(work + "/render.sbatch"), {"SLURM_ARRAY_TASK_ID=2", "SLURM_ARRAY_JOB_ID=1"}, "/", code);
    QVERIFY2(code == 0 && out.contains("rendered 1, kept 9"), qPrintable(out));
    runBash(QString::fromStdString(work + "/verify.sbatch"), {}, "/", code);
    QCOMPARE(code, 0);
  }
};

QTEST_APPLESS_MAIN(TestFarm)
#include "test_sequencer_farm.moc"
