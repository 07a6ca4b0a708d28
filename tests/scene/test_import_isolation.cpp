// Imports through Assimp run in hybridscape-import-worker (scene/import_isolation.h):
// the FBX that crashes Assimp 5.2.5 (double free) is a clear error and this
// process goes on; a file read by the worker is the same mesh, byte for byte,
// as one read here (single files and tiles); Cancel kills the worker at once
// (a stand-in worker that never ends, and the real one on a large PLY); a
// worker that dies of a signal or ends without a result is reported as such;
// without a worker the file is read here with a warning; OBJ never leaves
// this process; the worker's memory limit and watchdog are named when hit.
#include <QElapsedTimer>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/parallel.h"
#include "file_bytes.h"
#include "memory_group.h"
#include "mesh/mesh_import.h"
#include "mesh/tile_merge.h"
#include "scene/import_isolation.h"
#include "scene/import_pipeline.h"
#include "truncation.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

const std::string kData = HS_TEST_DATA_DIR "/mesh";
const std::string kCrashFbx = kData + "/crashes_assimp_embedded_texture.fbx";

// Sets an environment variable for one scope.
struct EnvVar {
  QByteArray name, old;
  bool had;
  EnvVar(const char* n, const QByteArray& value) : name(n), old(qgetenv(n)), had(qEnvironmentVariableIsSet(n)) {
    qputenv(n, value);
  }
  ~EnvVar() {
    if (had) qputenv(name.constData(), old);
    else qunsetenv(name.constData());
  }
};

// The children of this process still there (zombies included).
QStringList childProcesses() {
  QStringList out;
  const std::string self = std::to_string(getpid());
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream f(e.path() / "stat");
    std::string line;
    std::getline(f, line);
    // pid (comm) state ppid ...
    const size_t close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    std::string state, ppid;
    rest >> state >> ppid;
    if (ppid == self) out << QString::fromStdString(pid + " " + line.substr(0, close + 1) + " " + state);
  }
  return out;
}

// /proc/PID/oom_score_adj, or -10000 when it cannot be read.
int oomScoreAdj(const QString& pid) {
  std::ifstream f("/proc/" + pid.toStdString() + "/oom_score_adj");
  int adj = -10000;
  f >> adj;
  return adj;
}

bool sameTextures(const mesh::MeshData& a, const mesh::MeshData& b) {
  if (a.textures.size() != b.textures.size()) return false;
  for (size_t i = 0; i < a.textures.size(); ++i)
    if (a.textures[i].rgba != b.textures[i].rgba || a.textures[i].encoded != b.textures[i].encoded ||
        a.textures[i].name != b.textures[i].name)
      return false;
  return true;
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// An ASCII PLY grid tile of n x n cells of 1 m starting at x0 (tiles with
// x0 = 0 and x0 = n share a border).
void writePlyTile(const std::string& path, double x0, int n) {
  std::ostringstream s;
  s << "ply\nformat ascii 1.0\nelement vertex " << (n + 1) * (n + 1)
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2 * n * n
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s << x0 + i << " " << j << " " << 0.25 * std::sin(0.5 * (x0 + i)) << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
    }
  writeText(path, s.str());
}

// A binary PLY of an n x n grid (2 n^2 triangles): large enough that Assimp
// needs a while.
void writeLargePly(const std::string& path, int n) {
  std::ofstream f(path, std::ios::binary);
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << (n + 1) * (n + 1)
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2 * n * n
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float p[3] = {float(i) * 0.1f, float(j) * 0.1f, 0.05f * std::sin(0.1f * float(i + j))};
      f.write(reinterpret_cast<const char*>(p), sizeof p);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const uint8_t three = 3;
      const int t1[3] = {a, b, d}, t2[3] = {a, d, c};
      f.write(reinterpret_cast<const char*>(&three), 1);
      f.write(reinterpret_cast<const char*>(t1), sizeof t1);
      f.write(reinterpret_cast<const char*>(&three), 1);
      f.write(reinterpret_cast<const char*>(t2), sizeof t2);
    }
}

bool contains(const std::string& s, const char* what) { return s.find(what) != std::string::npos; }

}  // namespace

class TestImportIsolation : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const char* name) const { return tmp_.filePath(name).toStdString(); }

  // A stand-in worker: a shell script with `body`.
  QByteArray fakeWorker(const char* name, const QString& body) {
    const QString file = tmp_.filePath(name);
    QFile f(file);
    if (!f.open(QIODevice::WriteOnly)) qFatal("cannot write %s", qPrintable(file));
    f.write(("#!/bin/sh\n" + body + "\n").toUtf8());
    f.close();
    f.setPermissions(QFile::ReadOwner | QFile::WriteOwner | QFile::ExeOwner);
    return file.toLocal8Bit();
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    qunsetenv("HS_IMPORT_WORKER");
    std::string looked;
    const std::string worker = scene::findImportWorker(&looked);
    QVERIFY2(!worker.empty(), ("no worker; looked at " + looked).c_str());
    QVERIFY2(fs::exists(kCrashFbx), kCrashFbx.c_str());
  }

  // ---- (1) the file that crashes Assimp --------------------------------------------

  void crashingFbxIsAClearError() {
    scene::MeshImportRequest request;
    request.files = {kCrashFbx};
    const scene::ImportedMesh r = scene::importMeshFiles(request);
    QVERIFY(!r.ok());
    QVERIFY(!r.cancelled);
    QVERIFY(!r.mesh);
    // "<path>: the FBX reader (Assimp) crashed on this file (SIGABRT); it is
    // probably damaged. Nothing was imported."
    for (const char* w : {"crashes_assimp_embedded_texture.fbx: ", "the FBX reader (Assimp) crashed on this file",
                          "(SIGABRT)", "probably damaged", "Nothing was imported."})
      QVERIFY2(contains(r.error, w), qPrintable(QString("'%1' not in: %2").arg(w, QString::fromStdString(r.error))));
    QVERIFY2(r.error.find('\n') == std::string::npos, r.error.c_str());
    // Still here, and able to import the next file.
    request.files = {kData + "/textured_quad.glb"};
    QVERIFY(scene::importMeshFiles(request).ok());
  }

  void crashingTileNamesTheTile() {
    writePlyTile(path("tile_a.ply"), 0, 4);
    scene::MeshImportRequest request;
    request.files = {path("tile_a.ply"), kCrashFbx};
    const scene::ImportedMesh r = scene::importMeshFiles(request);
    QVERIFY(!r.ok());
    QVERIFY2(contains(r.error, "tile 2 of 2: ") && contains(r.error, "crashes_assimp_embedded_texture.fbx") &&
                 contains(r.error, "crashed"),
             r.error.c_str());
  }

  // ---- (2) the same mesh as read in this process ---------------------------------------

  void workerGivesTheSameMesh_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("up");
    QTest::newRow("glb, embedded texture") << QString::fromStdString(kData + "/textured_quad.glb") << int(mesh::UpAxis::Auto);
    QTest::newRow("fbx, texture beside it") << QString::fromStdString(kData + "/textured_quad.fbx") << int(mesh::UpAxis::Auto);
    QTest::newRow("ply, z up") << QString::fromStdString(kData + "/quad_and_triangle.ply") << int(mesh::UpAxis::Z);
  }
  void workerGivesTheSameMesh() {
    QFETCH(QString, file);
    QFETCH(int, up);
    mesh::ImportOptions o;
    o.up = mesh::UpAxis(up);
    o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Manual;
    o.geoOffset = glm::dvec3(500000.125, 4400000.25, 100.5);
    const mesh::ImportResult here = mesh::importMesh(file.toStdString(), o);
    QVERIFY2(here.ok(), here.error.c_str());
    std::atomic<int> progressCalls{0};
    double lastFraction = -1;
    Progress progress([&](double f, std::string_view) {
      ++progressCalls;
      lastFraction = f;
    });
    const mesh::ImportResult there = scene::importMeshIsolated(file.toStdString(), o, &progress);
    QVERIFY2(there.ok(), there.error.c_str());
    QCOMPARE(mesh::contentHash(*there.mesh), mesh::contentHash(*here.mesh));
    QVERIFY(sameTextures(*there.mesh, *here.mesh));
    QCOMPARE(there.mesh->origin, here.mesh->origin);
    // The report too (its time is the whole time, worker included).
    QCOMPARE(there.report.file, here.report.file);
    QCOMPARE(there.report.reader, here.report.reader);  // the same reader in the worker
    QCOMPARE(there.report.trianglesIn, here.report.trianglesIn);
    QCOMPARE(there.report.verticesOut, here.report.verticesOut);
    QCOMPARE(there.report.normalsGenerated, here.report.normalsGenerated);
    QCOMPARE(there.report.upAxisConverted, here.report.upAxisConverted);
    QCOMPARE(there.report.warnings, here.report.warnings);  // no "read inside this process"
    QCOMPARE(there.report.geoOffset, here.report.geoOffset);
    QCOMPARE(there.report.geoOffsetSource, here.report.geoOffsetSource);
    QVERIFY(there.report.seconds > 0.0);
    // Progress came through from the worker.
    QVERIFY(progressCalls > 1);
    QCOMPARE(lastFraction, 1.0);

    // And through the pipeline the editor and the CLI use.
    scene::MeshImportRequest request;
    request.files = {file.toStdString()};
    request.import = o;
    const scene::ImportedMesh viaPipeline = scene::importMeshFiles(request);
    QVERIFY2(viaPipeline.ok(), viaPipeline.error.c_str());
    QCOMPARE(mesh::contentHash(*viaPipeline.mesh), mesh::contentHash(*here.mesh));
  }

  void tilesThroughTheWorker() {
    writePlyTile(path("west.ply"), 0, 6);
    writePlyTile(path("east.ply"), 6, 6);
    mesh::TileImportOptions t;
    t.import.up = mesh::UpAxis::Z;
    const mesh::TileImportResult here = mesh::importTiles({path("west.ply"), path("east.ply")}, t);
    QVERIFY2(here.ok(), here.error.c_str());
    scene::MeshImportRequest request;
    request.files = {path("west.ply"), path("east.ply")};
    request.import.up = mesh::UpAxis::Z;
    const scene::ImportedMesh there = scene::importMeshFiles(request);
    QVERIFY2(there.ok(), there.error.c_str());
    QCOMPARE(there.tiles.size(), size_t(2));
    QCOMPARE(mesh::contentHash(*there.mesh), mesh::contentHash(*here.mesh));
    QCOMPARE(there.tileBorderVerticesMerged, here.borderVerticesMerged);
    QVERIFY(there.tileBorderVerticesMerged > 0);
  }

  // One pool serves many files with one worker: each the same mesh as read
  // here; a reader error keeps the worker, a crash loses it and the next
  // file gets a new one; nothing is left running when the pool goes.
  void onePoolKeepsItsWorkerAcrossFiles() {
    const std::string glb = kData + "/textured_quad.glb";
    const mesh::ImportResult here = mesh::importMesh(glb);
    QVERIFY2(here.ok(), here.error.c_str());
    writeText(path("garbage.fbx"), "this is not an FBX file at all\n");
    {
      scene::ImportWorkerPool pool;
      for (int i = 0; i < 4; ++i) {
        const mesh::ImportResult r = pool.read(glb, {});
        QVERIFY2(r.ok(), r.error.c_str());
        QCOMPARE(mesh::contentHash(*r.mesh), mesh::contentHash(*here.mesh));
        QVERIFY(sameTextures(*r.mesh, *here.mesh));
        QCOMPARE(r.report.warnings, here.report.warnings);
      }
      QCOMPARE(pool.workersStarted(), 1u);
      const QStringList kept = childProcesses();
      QCOMPARE(kept.size(), qsizetype(1));  // kept, waiting for the next file
      // The kernel's first choice when memory runs out, before this process
      // (the editor, with the user's scene): see tools/import_worker/main.cpp.
      QCOMPARE(oomScoreAdj(kept[0].section(' ', 0, 0)), 1000);
      const int self = oomScoreAdj(QString::number(getpid()));
      QVERIFY2(self > -10000 && self < 1000, qPrintable(QString::number(self)));  // this process: as it was
      const mesh::ImportResult garbage = pool.read(path("garbage.fbx"), {});
      QCOMPARE(garbage.error, mesh::importMesh(path("garbage.fbx")).error);
      QVERIFY(pool.read(glb, {}).ok());
      QCOMPARE(pool.workersStarted(), 1u);
      const mesh::ImportResult crash = pool.read(kCrashFbx, {});
      QVERIFY2(contains(crash.error, "crashed on this file (SIGABRT)"), crash.error.c_str());
      const mesh::ImportResult after = pool.read(glb, {});
      QVERIFY2(after.ok(), after.error.c_str());
      QCOMPARE(mesh::contentHash(*after.mesh), mesh::contentHash(*here.mesh));
      QCOMPARE(pool.workersStarted(), 2u);
    }
    QVERIFY2(childProcesses().isEmpty(), qPrintable(childProcesses().join("; ")));
  }

  // Tiles through the worker are read at once, as many as the cores and
  // the workers' memory limit allow; tiles the own readers read, one by one.
  void tileReadParallelismFollowsCoresAndMemoryLimit() {
    const std::vector<std::string> fbx = {"a.fbx", "b.fbx", "c.fbx", "d.fbx"};
    const unsigned cores = availableThreads();  // the CPUs this process may use
    {
      EnvVar limit("HS_IMPORT_MEMORY_LIMIT", "0");  // no limit: the cores decide
      QCOMPARE(scene::tileReadParallelism(fbx, {}), std::min(cores, 4u));
      QCOMPARE(scene::tileReadParallelism({"a.fbx"}, {}), 1u);
      QCOMPARE(scene::tileReadParallelism({"a.obj", "b.obj"}, {}), 1u);  // own reader, all cores each
      QCOMPARE(scene::tileReadParallelism({"a.ply", "b.ply"}, {}), 1u);
      mesh::ImportOptions viaAssimp;
      viaAssimp.reader = mesh::Reader::Assimp;
      QCOMPARE(scene::tileReadParallelism({"a.ply", "b.ply"}, viaAssimp), std::min(cores, 2u));
    }
    {
      EnvVar limit("HS_IMPORT_MEMORY_LIMIT", "100%");  // one worker may take all memory
      QCOMPARE(scene::tileReadParallelism(fbx, {}), 1u);
    }
    {
      EnvVar limit("HS_IMPORT_MEMORY_LIMIT", "34%");  // two fit
      QCOMPARE(scene::tileReadParallelism(fbx, {}), std::min(cores, 2u));
    }
  }

  // Errors of the reader pass through as they are.
  void readerErrorsPassThrough() {
    writeText(path("garbage.fbx"), "this is not an FBX file at all\n");
    const mesh::ImportResult here = mesh::importMesh(path("garbage.fbx"));
    const mesh::ImportResult there = scene::importMeshIsolated(path("garbage.fbx"), {});
    QVERIFY(!here.ok() && !there.ok());
    QCOMPARE(there.error, here.error);
    const mesh::ImportResult missing = scene::importMeshIsolated(path("missing.ply"), {});
    QCOMPARE(missing.error, mesh::importMesh(path("missing.ply")).error);
  }

  // Every format read through the worker, cut short at seven lengths (a
  // worker costs ~0.2 s to start; tests/mesh cuts PLY at every byte):
  // an error naming the file, or (a cut that only lost bytes the format
  // does not need) the whole mesh; never a part of it without a word.
  void filesCutShort_data() {
    QTest::addColumn<QString>("file");
    QTest::newRow("glb") << QString::fromStdString(kData + "/textured_quad.glb");
    QTest::newRow("fbx") << QString::fromStdString(kData + "/textured_quad.fbx");
    QTest::newRow("ascii ply") << QString::fromStdString(kData + "/quad_and_triangle.ply");
    QTest::newRow("binary ply") << QString::fromStdString(path("small_binary.ply"));
  }
  void filesCutShort() {
    QFETCH(QString, file);
    writeLargePly(path("small_binary.ply"), 6);
    const std::string whole = hs::test::readFile(file.toStdString());
    QVERIFY(!whole.empty());
    scene::MeshImportRequest request;
    request.import.up = mesh::UpAxis::Z;
    request.files = {file.toStdString()};
    const scene::ImportedMesh full = scene::importMeshFiles(request);
    QVERIFY2(full.ok(), full.error.c_str());
    const std::string ext = file.toStdString().substr(file.toStdString().rfind('.'));
    const std::string cut = path("cut") + ext;
    fs::copy_file(kData + "/checker_4x2.png", path("checker_4x2.png"), fs::copy_options::overwrite_existing);  // the FBX's texture
    request.files = {cut};
    size_t errors = 0;
    for (size_t n : hs::test::cutLengths(whole.size(), whole.size() / 6 + 1)) {
      hs::test::writeFile(cut, whole.substr(0, n));
      const scene::ImportedMesh r = scene::importMeshFiles(request);
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + " of " +
                               QByteArray::number(qulonglong(whole.size())) + ": ";
      if (!r.ok()) {
        QVERIFY2(!r.cancelled, where + r.error.c_str());
        QVERIFY2(contains(r.error, cut.c_str()), where + r.error.c_str());
        ++errors;
        continue;
      }
      QVERIFY2(mesh::contentHash(*r.mesh) == mesh::contentHash(*full.mesh), where + "a different mesh, no error");
    }
    QVERIFY(errors > 0);
  }

  // ---- (3) Cancel kills the worker ---------------------------------------------------

  void cancelKillsAWorkerThatNeverEnds() {
    const QByteArray pidFile = tmp_.filePath("worker.pid").toLocal8Bit();
    EnvVar env("HS_IMPORT_WORKER", fakeWorker("hang.sh", QString("echo $$ > '%1'\n"
                                                                 "echo 'progress 0.2500 Reading with Assimp'\n"
                                                                 "exec sleep 120")
                                                             .arg(QString::fromLocal8Bit(pidFile))));
    // Through the pipeline, with the progress bar's Cancel: the worker
    // reports once, then nothing, and Cancel must still get through.
    std::atomic<bool> sawProgress{false};
    Progress progress([&](double f, std::string_view stage) {
      if (f > 0.0 && stage == "Reading with Assimp") sawProgress = true;
    });
    scene::MeshImportRequest request;
    request.files = {kData + "/textured_quad.glb"};
    scene::ImportedMesh result;
    std::atomic<bool> done{false};
    std::thread worker([&] {
      result = scene::importMeshFiles(request, &progress);
      done = true;
    });
    QTRY_VERIFY_WITH_TIMEOUT(sawProgress.load(), 10000);
    QVERIFY(!done);
    QElapsedTimer timer;
    timer.start();
    progress.cancel();
    QTRY_VERIFY_WITH_TIMEOUT(done.load(), 5000);
    worker.join();
    const qint64 ms = timer.elapsed();
    qInfo("cancel took %lld ms", ms);
    QVERIFY2(ms < 1000, qPrintable(QString("%1 ms").arg(ms)));
    QVERIFY(result.cancelled);
    QVERIFY(!result.mesh);
    // The worker is gone (killed and reaped), not left sleeping.
    QFile f(QString::fromLocal8Bit(pidFile));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const pid_t pid = pid_t(f.readAll().trimmed().toLong());
    QVERIFY(pid > 0);
    QVERIFY(::kill(pid, 0) == -1 && errno == ESRCH);
    QVERIFY2(childProcesses().isEmpty(), qPrintable(childProcesses().join("; ")));
  }

  void cancelKillsTheRealWorkerMidRead() {
    writeLargePly(path("large.ply"), 1000);  // two million triangles, 38 MB
    std::atomic<bool> sawProgress{false};
    Progress progress([&](double f, std::string_view) {
      if (f > 0.0) sawProgress = true;
    });
    mesh::ImportResult result;
    std::atomic<bool> done{false};
    QElapsedTimer total;
    total.start();
    std::thread worker([&] {
      result = scene::importMeshIsolated(path("large.ply"), {}, &progress);
      done = true;
    });
    QTRY_VERIFY_WITH_TIMEOUT(sawProgress.load(), 20000);
    QElapsedTimer timer;
    timer.start();
    progress.cancel();
    QTRY_VERIFY_WITH_TIMEOUT(done.load(), 5000);
    worker.join();
    qInfo("cancelled after %lld ms of reading, within %lld ms", total.elapsed() - timer.elapsed(), timer.elapsed());
    QVERIFY2(timer.elapsed() < 1000, qPrintable(QString("%1 ms").arg(timer.elapsed())));
    QVERIFY(result.cancelled);
    QVERIFY(!result.ok());
    QVERIFY2(childProcesses().isEmpty(), qPrintable(childProcesses().join("; ")));
  }

  // ---- how a worker ends ---------------------------------------------------------

  void workerKilledBySignal() {
    EnvVar env("HS_IMPORT_WORKER", fakeWorker("segv.sh", "ulimit -c 0\nkill -SEGV $$"));
    const mesh::ImportResult r = scene::importMeshIsolated(path("rock.fbx"), {});
    QVERIFY(!r.ok() && !r.cancelled);
    QVERIFY2(contains(r.error, "rock.fbx: the FBX reader (Assimp) crashed on this file (SIGSEGV)"), r.error.c_str());
  }

  void workerEndsWithoutAResult() {
    EnvVar env("HS_IMPORT_WORKER", fakeWorker("quit.sh", "echo 'something went wrong' >&2\nexit 7"));
    const mesh::ImportResult r = scene::importMeshIsolated(path("rock.glb"), {});
    QVERIFY(!r.ok() && !r.cancelled);
    QVERIFY2(contains(r.error, "rock.glb: the glTF reader (Assimp) stopped without a result (exit code 7: something went wrong)"),
             r.error.c_str());
    // Exit code 0 but nothing written: a torn result is not a mesh.
    EnvVar env2("HS_IMPORT_WORKER", fakeWorker("silent.sh", "printf 'HSIMPRES' >&3\nexit 0"));
    const mesh::ImportResult s = scene::importMeshIsolated(path("rock.glb"), {});
    QVERIFY(!s.ok());
    QVERIFY2(contains(s.error, "stopped without a result (exit code 0: the result is cut short"), s.error.c_str());
  }

  // ---- limits: memory and the watchdog ------------------------------------------------

  // A worker that reports once and then nothing is stopped by the watchdog,
  // and the error says so (not "cancelled", not "crashed").
  void watchdogStopsAWorkerThatMakesNoProgress() {
    EnvVar env("HS_IMPORT_WORKER", fakeWorker("stuck.sh", "echo 'progress 0.1000 Reading with Assimp'\nexec sleep 120"));
    EnvVar watchdog("HS_IMPORT_WATCHDOG_S", "1");
    QElapsedTimer clock;
    clock.start();
    const mesh::ImportResult r = scene::importMeshIsolated(path("stuck.fbx"), {});
    QVERIFY2(clock.elapsed() < 20000, qPrintable(QString::number(clock.elapsed())));
    QVERIFY(!r.ok() && !r.cancelled);
    QVERIFY2(contains(r.error, "stuck.fbx: the FBX reader (Assimp) made no progress for 1 s") &&
                 contains(r.error, "stuck at 10%") && contains(r.error, "watchdog"),
             r.error.c_str());
    QVERIFY2(childProcesses().isEmpty(), qPrintable(childProcesses().join("; ")));
  }

  // The real worker under a small memory limit on a binary STL that needs
  // more (400k triangles: Assimp takes about 480 MB for it): a clean error
  // naming the file and the limit, not a crash or "damaged".
  void memoryLimitIsNamedWhenReached() {
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer reserves terabytes of address space and aborts when
    // an mmap fails, so a worker under RLIMIT_AS dies by SIGABRT before any
    // allocation can fail: the case means nothing in `scripts/hs sanitize`
    // (docs/reliability.md "Sanitizers"). The normal build runs it.
    QSKIP("RLIMIT_AS cannot bound a worker under AddressSanitizer");
#endif
    std::string stl(80, '\0');
    const uint32_t n = 400000;
    stl.append(reinterpret_cast<const char*>(&n), 4);
    for (uint32_t i = 0; i < n; ++i) {
      const float x = float(i % 1000), y = float(i / 1000);
      const float t[12] = {0, 0, 1, x, y, 0, x + 1, y, 0, x, y + 1, 0};
      stl.append(reinterpret_cast<const char*>(t), sizeof t);
      stl.append(2, '\0');
    }
    const std::string p = path("big.stl");
    hs::test::writeFile(p, stl);
    EnvVar limit("HS_IMPORT_MEMORY_LIMIT", "100");
    const mesh::ImportResult r = scene::importMeshIsolated(p, {});
    QVERIFY(!r.ok() && !r.cancelled);
    QVERIFY2(contains(r.error, p.c_str()) && contains(r.error, "out of memory") && contains(r.error, "memory limit") &&
                 contains(r.error, "100 MiB") && !contains(r.error, "damaged"),
             r.error.c_str());
    fs::remove(p);
  }

  // A lower limit set from outside (ulimit -v, a batch system) is kept: the
  // worker cannot raise a hard limit, and once every Assimp import failed
  // with an argument error under one. Run in a child, whose limit goes
  // with it; the limit is below the default share of this machine.
  void aLowerLimitFromOutsideIsKept() {
#if defined(__SANITIZE_ADDRESS__)
    QSKIP("RLIMIT_AS cannot bound a process under AddressSanitizer (see memoryLimitIsNamedWhenReached)");
#endif
    const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    const rlim_t outside = rlim_t(std::min(physical / 4, 8.0 * 1024 * 1024 * 1024));
    const pid_t child = fork();
    QVERIFY(child >= 0);
    if (child == 0) {
      const rlimit limit{outside, outside};
      if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
      const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.glb", {});
      if (!r.ok()) std::fprintf(stderr, "%s\n", r.error.c_str());
      _exit(r.ok() ? 0 : 1);
    }
    int status = 0;
    QCOMPARE(waitpid(child, &status, 0), child);
    QVERIFY2(WIFEXITED(status) && WEXITSTATUS(status) == 0, qPrintable(QString::number(status)));
  }

  // Under a control group's memory limit (a Slurm job, a container) the
  // share is of that limit, not of the machine: a worker sized by the
  // machine oversteps the job, and the kernel kills inside the group
  // instead of an allocation failing with a message. Run in a child moved
  // into a group made here (memory_group.h); each check is its own exit
  // code.
  void theShareIsOfTheControlGroupsLimit() {
    const uint64_t limit = uint64_t(1) << 30;
    const hs::test::MemoryGroup group(limit);
    if (!group.made)
      QSKIP(qPrintable(QString::fromStdString("no memory control group can be made here (" + group.why +
                                              "); tests/core/test_memory_limit checks the parser on made-up trees")));
    const std::vector<std::string> fbx = {"a.fbx", "b.fbx", "c.fbx", "d.fbx"};
    const pid_t child = fork();
    QVERIFY(child >= 0);
    if (child == 0) {
      if (!group.join()) _exit(2);
      scene::WorkerLimits limits;
      std::string error;
      ::unsetenv("HS_IMPORT_MEMORY_LIMIT");
      if (!scene::workerLimits(limits, error) || limits.memoryBytes != limit / 2) _exit(3);
      if (limits.memoryText != "50% of 1.0 GiB, the memory limit of control group " + group.relative) _exit(4);
      // 600 MiB a worker: 40 would fit the machine's memory, one the group's.
      ::setenv("HS_IMPORT_MEMORY_LIMIT", "600", 1);
      if (scene::tileReadParallelism(fbx, {}) != 1) _exit(5);
      // A worker under half the group's limit still reads a file.
      ::unsetenv("HS_IMPORT_MEMORY_LIMIT");
      const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.glb", {});
      if (!r.ok()) std::fprintf(stderr, "%s\n", r.error.c_str());
      _exit(r.ok() ? 0 : 6);
    }
    int status = 0;
    QCOMPARE(waitpid(child, &status, 0), child);
    QVERIFY2(WIFEXITED(status), qPrintable(QString::number(status)));
    QCOMPARE(WEXITSTATUS(status), 0);
  }

  void limitSettingsThatMakeNoSenseAreNamed() {
    {
      EnvVar limit("HS_IMPORT_MEMORY_LIMIT", "lots");
      const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.glb", {});
      QVERIFY2(!r.ok() && contains(r.error, "HS_IMPORT_MEMORY_LIMIT: 'lots'"), r.error.c_str());
    }
    {
      EnvVar watchdog("HS_IMPORT_WATCHDOG_S", "-1");
      const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.glb", {});
      QVERIFY2(!r.ok() && contains(r.error, "HS_IMPORT_WATCHDOG_S: '-1'"), r.error.c_str());
    }
    scene::WorkerLimits limits;
    std::string error;
    EnvVar share("HS_IMPORT_MEMORY_LIMIT", "25%");
    QVERIFY2(scene::workerLimits(limits, error), error.c_str());
    const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    QVERIFY(std::abs(double(limits.memoryBytes) - physical / 4) < 1e6);
    QCOMPARE(limits.watchdogSeconds, 300.0);
  }

  // ---- finding the worker --------------------------------------------------------

  void withoutAWorkerTheFileIsReadHereWithAWarning() {
    EnvVar env("HS_IMPORT_WORKER", "/nonexistent/hybridscape-import-worker");
    QCOMPARE(scene::findImportWorker(), std::string());
    const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.glb", {});
    QVERIFY2(r.ok(), r.error.c_str());
    bool warned = false;
    for (const auto& w : r.report.warnings)
      warned |= contains(w, "read inside this process") && contains(w, "/nonexistent/hybridscape-import-worker");
    QVERIFY(warned);
    QCOMPARE(mesh::contentHash(*r.mesh), mesh::contentHash(*mesh::importMesh(kData + "/textured_quad.glb").mesh));
  }

  void objStaysInThisProcess() {
    EnvVar env("HS_IMPORT_WORKER", fakeWorker("never.sh", "exit 9"));
    QVERIFY(!scene::readsWithAssimp(kData + "/textured_quad.obj", {}));
    const mesh::ImportResult r = scene::importMeshIsolated(kData + "/textured_quad.obj", {});
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.warnings.empty());
    // Forced through Assimp it is the worker's.
    mesh::ImportOptions o;
    o.reader = mesh::Reader::Assimp;
    QVERIFY(scene::readsWithAssimp(kData + "/textured_quad.obj", o));
    const mesh::ImportResult a = scene::importMeshIsolated(kData + "/textured_quad.obj", o);
    QVERIFY2(contains(a.error, "the OBJ reader (Assimp) stopped without a result (exit code 9)"), a.error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestImportIsolation)
#include "test_import_isolation.moc"
