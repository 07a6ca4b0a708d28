// Render-farm scripts: the job array's shape and command lines, quoting,
// valid bash. Runs of the scripts (acted out with bash, and on a real Slurm)
// use the real hybridscape-cli: tests/cli/test_cli_sequence.cpp and
// tests/farm/test_farm_slurm.cpp.
#include <QtTest>

#include <filesystem>

#include "sequencer/slurm_script.h"

using namespace hs::sequencer;
using hs::Image;
using hs::ImageView;
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

  // The farm run acted out with bash (every array task, then the check) uses
  // the real CLI now: tests/cli/test_cli_sequence.cpp,
  // farmSlurmScriptsActedOutWithBash; the run on a real Slurm is
  // tests/farm/test_farm_slurm.cpp.
};

QTEST_APPLESS_MAIN(TestFarm)
#include "test_sequencer_farm.moc"
