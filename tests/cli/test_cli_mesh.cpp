// `hybridscape-cli import` with the photogrammetry options, run as a user
// runs it: --decimate-to (count and share), --max-error, --lods, --origin
// (auto sidecar, by hand), several tiles as one asset, --clean, the printed
// summary and the --report fields, the thread count under a CPU binding,
// `info` listing the LODs, and bad values each refused in one line with the
// scene file left byte for byte.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <sched.h>

#include <cmath>

#include "cli_runner.h"
#include "core/parallel.h"
#include "file_bytes.h"
#include "mesh/mesh_import.h"
#include "scene/hscene_file.h"
#include "two_material_obj.h"

using namespace hs;
using hs::test::kCli;
using hs::test::readFile;
using hs::test::writeFile;

namespace {

const QString kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

using Run = hs::test::CliRun;

QJsonObject parseJson(const QByteArray& text) { return QJsonDocument::fromJson(text).object(); }

// A gently curved grid tile of n x n cells of `step` metres, its columns
// starting at x0, written relative to its own offset (as Pix4D does); z up.
void writeTile(const QString& path, double x0, int n, double step) {
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly)) qFatal("cannot write %s", qPrintable(path));
  QByteArray text;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + i * step, y = j * step;
      text += QByteArray("v ") + QByteArray::number(i * step, 'f', 6) + " " + QByteArray::number(y, 'f', 6) + " " +
              QByteArray::number(0.3 * std::sin(x * 0.4) * std::cos(y * 0.3), 'f', 6) + "\n";
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
      text += "f " + QByteArray::number(a) + " " + QByteArray::number(b) + " " + QByteArray::number(d) + "\n";
      text += "f " + QByteArray::number(a) + " " + QByteArray::number(d) + " " + QByteArray::number(c) + "\n";
    }
  f.write(text);
}

}  // namespace

class TestCliMesh : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

  QString path(const QString& name) const { return tmp_.filePath(name); }

  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }

  QString newScene(const QString& name) { return test::newSceneWithCli(path(name), tmp_.path()); }

  std::optional<scene::SceneState> load(const QString& file) {
    std::string error;
    auto s = scene::loadScene(file.toStdString(), error);
    if (!s) qWarning("%s", error.c_str());
    return s;
  }

  QJsonObject readReport(const QString& file) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return parseJson(f.readAll());
  }

  // A refusal: exit code, exactly one line on stderr naming `what`, and the
  // scene file as it was, byte for byte.
  void expectRefused(const QStringList& args, int code, const QStringList& what, const QString& scene) {
    const std::string before = readFile(scene.toStdString());
    const Run r = cli(args);
    QVERIFY2(r.code == code, qPrintable(QString("exit %1, expected %2: %3").arg(r.code).arg(code).arg(r.err)));
    QVERIFY2(r.err.count('\n') == 1 && r.err.endsWith('\n'), qPrintable("not one line: " + r.err));
    for (const QString& w : what) QVERIFY2(r.err.contains(w), qPrintable(QString("'%1' not in: %2").arg(w, r.err)));
    QVERIFY(readFile(scene.toStdString()) == before);
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
  }

  // The refinement (max_error_refine.h) runs unless --no-refine: its
  // report says what moved, and the measured Hausdorff is the lower one.
  void noRefineKeepsTheDecimatorsPlaces() {
    QJsonObject runs[2];
    for (int off = 0; off < 2; ++off) {
      const QString f = newScene(off ? "plain.hscene" : "refined.hscene");
      const QString report = path(off ? "plain.json" : "refined.json");
      QStringList args = {"import", kBunny, f, "--decimate-to", "10%", "--report", report};
      if (off) args << "--no-refine";
      const Run r = cli(args);
      QVERIFY2(r.code == 0, qPrintable(r.err));
      QCOMPARE(r.out.contains("refinement"), !off);
      runs[off] = readReport(report)["processing"].toObject();
    }
    const QJsonObject refinement = runs[0]["refinement"].toObject();
    QVERIFY(refinement["moved"].toInt() > 0 && refinement["moved"].toInt() <= refinement["candidates"].toInt());
    QVERIFY(refinement["largest_after_m"].toDouble() < refinement["largest_before_m"].toDouble());
    QVERIFY(refinement["seconds"].isDouble());
    QVERIFY(runs[1]["refinement"].isNull());
    QCOMPARE(runs[0]["decimation"].toObject()["triangles_out"], runs[1]["decimation"].toObject()["triangles_out"]);
    QVERIFY(runs[0]["error"].toObject()["hausdorff_m"].toDouble() < runs[1]["error"].toObject()["hausdorff_m"].toDouble());
  }

  // --certify: the report's certified upper bound, printed and stored.
  void certifyBoundsTheHausdorff() {
    const QString f = newScene("certified.hscene");
    const QString report = path("certified.json");
    const Run r = cli({"import", kBunny, f, "--decimate-to", "10%", "--certify", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("hausdorff_certified"), qPrintable(r.out));
    const QJsonObject e = readReport(report)["processing"].toObject()["error"].toObject();
    const QJsonObject c = e["hausdorff_certified"].toObject();
    QVERIFY(c["upper_m"].toDouble() >= e["hausdorff_m"].toDouble());
    QVERIFY(c["upper_m"].toDouble() < 1.5 * e["hausdorff_m"].toDouble());
    QVERIFY(c["pieces"].toDouble() > 0 && c["seconds"].isDouble());
  }

  // The example: a count target, LODs, and a report with plain names.
  void decimateToACountWithLodsAndReport() {
    const QString f = newScene("count.hscene");
    const QString report = path("count.json");
    const Run r = cli({"import", kBunny, f, "--decimate-to", "20k", "--lods", "3", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    // The summary names the fields as the report does.
    for (const char* key : {"imported", "hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "flipped_normals",
                            "uv_displacement_texels", "boundary_seam_vertices_moved", "area_change_rel",
                            "volume_change_rel", "non_manifold_edges_in", "non_manifold_vertices_in", "seconds", "lods[3]"})
      QVERIFY2(r.out.contains(key), qPrintable(QString("'%1' not printed:\n%2").arg(key, r.out)));

    const QJsonObject rep = readReport(report);
    QCOMPARE(rep["file"].toString(), kBunny);        // the import's fields, as before
    QCOMPARE(rep["triangles_out"].toInt(), 69451);
    const QJsonObject p = rep["processing"].toObject();
    // The target or one below it: an interior collapse removes two faces,
    // so from 20,001 the last one lands on 19,999 (decimate.h: stops once
    // the count is at most the target).
    const int trianglesOut = p["decimation"].toObject()["triangles_out"].toInt();
    QVERIFY2(trianglesOut == 20000 || trianglesOut == 19999, qPrintable(QString::number(trianglesOut)));
    QCOMPARE(p["decimation"].toObject()["target_reached"].toBool(), true);
    const QJsonObject e = p["error"].toObject();
    for (const char* key : {"hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "mean_rel", "bbox_diagonal_m",
                            "area_in_m2", "area_out_m2", "area_change_rel", "volume_change_rel", "seconds"})
      QVERIFY2(e[key].isDouble(), key);
    for (const char* key : {"flipped_normals", "boundary_seam_vertices_moved", "non_manifold_edges_in",
                            "non_manifold_edges_out", "non_manifold_vertices_in", "non_manifold_vertices_out"})
      QVERIFY2(e[key].isDouble(), key);
    QVERIFY(e["uv_displacement_texels"].isNull());  // the bunny has no texture
    const double diag = e["bbox_diagonal_m"].toDouble();
    QVERIFY(std::abs(e["hausdorff_rel"].toDouble() - e["hausdorff_m"].toDouble() / diag) < 1e-9);
    QVERIFY(e["hausdorff_rel"].toDouble() > 0 && e["hausdorff_rel"].toDouble() < 0.01);
    QCOMPARE(e["boundary_seam_vertices_moved"].toInt(), 0);
    QVERIFY(p["cleaning"].isObject());
    const QJsonArray lods = p["lods"].toArray();
    QCOMPARE(lods.size(), 4);  // level 0 and three coarser
    for (int k = 1; k < 4; ++k) {
      QVERIFY(lods[k].toObject()["triangles"].toInt() < lods[k - 1].toObject()["triangles"].toInt());
      QVERIFY(lods[k].toObject()["hausdorff_m"].toDouble() >= lods[k - 1].toObject()["hausdorff_m"].toDouble());
    }

    // The scene holds the decimated mesh, its levels and the report.
    auto s = load(f);
    QVERIFY(s);
    const scene::MeshAsset& a = s->assets.begin()->second;
    QCOMPARE(a.data->triangleCount(), size_t(trianglesOut));
    QCOMPARE(a.lods.size(), size_t(3));
    // The report's numbers read back to the same doubles (meshproc/report_json.h).
    QCOMPARE(lods[3].toObject()["hausdorff_m"].toDouble(), a.lods[2].hausdorff);
    QVERIFY(!a.processReport.is_null());

    // info and info --json list the levels with their errors.
    const Run text = cli({"info", f});
    QCOMPARE(text.code, 0);
    const QString lodLine = QString("LODs: 0: %1 triangles; 1: %2 triangles, hausdorff_m")
                                .arg(trianglesOut)
                                .arg(lods[1].toObject()["triangles"].toInt());
    QVERIFY2(text.out.contains(lodLine), qPrintable(text.out));
    QVERIFY(text.out.contains(QString("processed: decimated 69451 -> %1 triangles, hausdorff_m").arg(trianglesOut)));
    const QJsonObject info = parseJson(cli({"info", f, "--json"}).out.toUtf8());
    const QJsonArray infoLods = info["assets"].toArray()[0].toObject()["lods"].toArray();
    QCOMPARE(infoLods.size(), 4);
    QCOMPARE(infoLods[0].toObject()["triangles"].toInt(), trianglesOut);
    QCOMPARE(infoLods[0].toObject()["hausdorff_m"].toDouble(), 0.0);
    QCOMPARE(infoLods[1].toObject()["triangles"].toInt(), lods[1].toObject()["triangles"].toInt());
    QCOMPARE(infoLods[3].toObject()["hausdorff_m"].toDouble(), a.lods[2].hausdorff);
    QVERIFY(info["assets"].toArray()[0].toObject()["process_report"].toObject()["error"].isObject());
  }

  void decimateToAShare() {
    const QString f = newScene("share.hscene");
    const Run r = cli({"import", kBunny, f, "--decimate-to", "10%"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    auto s = load(f);
    QVERIFY(s);
    const size_t t = s->assets.begin()->second.data->triangleCount();
    QVERIFY2(std::abs(double(t) - 6945.0) <= 2.0, qPrintable(QString::number(t)));
    QVERIFY(s->assets.begin()->second.lods.empty());
  }

  // Bound to one CPU (as taskset, or a farm's binding of a job to its
  // cores, leaves a process), an import decimates on one thread and prints
  // no oneTBB warning; unbound, it uses every CPU it may. The thread count
  // follows the process's affinity mask, not the machine's CPUs: counted
  // from the machine, it asked oneTBB for a worker the mask did not allow,
  // and oneTBB printed "TBB Warning: The number of workers is currently
  // limited to 0" into the run's output.
  void boundToOneCpuDecimatesOnOneThread() {
    if (allowedCpus() < 2) QSKIP("this test process has one CPU: binding the CLI to one changes nothing");
    cpu_set_t mine;
    CPU_ZERO(&mine);
    QCOMPARE(sched_getaffinity(0, sizeof mine, &mine), 0);
    int cpu = 0;
    while (!CPU_ISSET(cpu, &mine)) ++cpu;
    auto importWith = [&](const QString& name, bool bound) {
      const QString f = newScene(name + ".hscene");
      auto bindToOne = [cpu] {
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpu, &one);
        sched_setaffinity(0, sizeof one, &one);
      };
      return test::runCli({"import", kBunny, f, "--decimate-to", "50%", "--report", path(name + ".json")},
                          tmp_.path(), 120000, bound ? std::function<void()>(bindToOne) : std::function<void()>());
    };
    const Run bound = importWith("bound", true);
    QVERIFY2(bound.code == 0, qPrintable(bound.err));
    QVERIFY2(!bound.err.contains("TBB") && !bound.out.contains("TBB"), qPrintable(bound.err + bound.out));
    QCOMPARE(readReport(path("bound.json"))["processing"].toObject()["decimation"].toObject()["threads"].toInt(), 1);
    const Run free = importWith("unbound", false);
    QVERIFY2(free.code == 0, qPrintable(free.err));
    QCOMPARE(readReport(path("unbound.json"))["processing"].toObject()["decimation"].toObject()["threads"].toInt(),
             CPU_COUNT(&mine));
  }

  void maxErrorIsMet() {
    const QString f = newScene("maxerror.hscene");
    const QString report = path("maxerror.json");
    // The bunny is 0.15 m tall: 0.5 mm allows a lot of decimation, not all.
    const Run r = cli({"import", kBunny, f, "--max-error", "0.0005", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const QJsonObject p = readReport(report)["processing"].toObject();
    QVERIFY(p["error"].toObject()["hausdorff_m"].toDouble() <= 0.0005);
    const int out = p["decimation"].toObject()["triangles_out"].toInt();
    QVERIFY2(out < 69451 / 2 && out > 100, qPrintable(QString::number(out)));
    QCOMPARE(p["options"].toObject()["max_error_m"].toDouble(), 0.0005);
  }

  void cleanOnlyAndPlainImport() {
    const QString f = newScene("clean.hscene");
    const QString report = path("clean.json");
    Run r = cli({"import", kBunny, f, "--clean", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QJsonObject p = readReport(report)["processing"].toObject();
    QVERIFY(p["cleaning"].isObject());
    QVERIFY(p["decimation"].isNull());
    QVERIFY(p["error"].isNull());
    // Without any processing option: as before, no processing report.
    r = cli({"import", kBunny, f, "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(readReport(report)["processing"].isNull());
    auto s = load(f);
    QVERIFY(s);
    QCOMPARE(s->assets.size(), size_t(2));
    QVERIFY(s->assets.rbegin()->second.processReport.is_null());
  }

  // Two tiles at UTM coordinates, each with its Pix4D offset: one asset,
  // every vertex where the offsets put it, the shared border welded.
  void tilesWithOffsetSidecars() {
    QDir().mkpath(path("tiles/a"));
    QDir().mkpath(path("tiles/b"));
    writeTile(path("tiles/a/tile.obj"), 0.0, 20, 1.0);
    writeTile(path("tiles/b/tile.obj"), 20.0, 20, 1.0);
    const glm::dvec3 site(656000.0, 5514500.0, 1700.0);
    auto writeOffset = [](const QString& file, const glm::dvec3& o) {
      QFile f(file);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write(QString("%1 %2 %3\n").arg(o.x, 0, 'f', 3).arg(o.y, 0, 'f', 3).arg(o.z, 0, 'f', 3).toUtf8());
    };
    writeOffset(path("tiles/a/tile_offset.xyz"), site);
    writeOffset(path("tiles/b/tile_offset.xyz"), site + glm::dvec3(20.0, 0.0, 0.0));
    const QString f = newScene("tiles.hscene");
    const QString report = path("tiles.json");
    const Run r = cli({"import", path("tiles/a/tile.obj"), path("tiles/b/tile.obj"), f, "--up", "z", "--origin", "auto",
                       "--decimate-to", "50%", "--lods", "1", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("and 1 more tiles"));
    QVERIFY(r.out.contains("Tiles:"));
    const QJsonObject rep = readReport(report);
    QCOMPARE(rep["tiles"].toArray().size(), 2);
    QCOMPARE(rep["processing"].toObject()["tiles"].toObject()["border_vertices_merged"].toInt(), 21);
    QVERIFY(rep["tiles"].toArray()[1].toObject()["geo_offset"].toObject()["source"].toString().endsWith("tile_offset.xyz"));

    auto s = load(f);
    QVERIFY(s);
    QCOMPARE(s->assets.size(), size_t(1));
    const scene::MeshAsset& a = s->assets.begin()->second;
    // 2 x 20 x 20 x 2 at 50%; a collapse removes two triangles, so up to two fewer.
    QVERIFY(a.data->triangleCount() <= 800 && a.data->triangleCount() >= 798);
    // Every vertex inside the site's 40 x 20 m, at UTM coordinates.
    const scene::Entity& e = s->entities.at(s->findByName("tile"));
    const glm::dmat4 w = s->worldMatrix(e.id);
    for (const glm::vec3& p : a.data->positions) {
      const glm::dvec3 q = glm::dvec3(w * glm::dvec4(glm::dvec3(p), 1.0)) - site;
      QVERIFY2(q.x > -1e-3 && q.x < 40.001 && q.y > -1e-3 && q.y < 20.001 && std::abs(q.z) < 0.31,
               qPrintable(QString("%1 %2 %3").arg(q.x).arg(q.y).arg(q.z)));
    }
  }

  void originByHand() {
    writeTile(path("plain.obj"), 0.0, 4, 1.0);
    const QString f = newScene("origin.hscene");
    const Run r = cli({"import", path("plain.obj"), f, "--up", "z", "--origin", "500000,4400000,300"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("georeferencing offset 500000.000,4400000.000,300.000"));
    auto s = load(f);
    QVERIFY(s);
    const glm::dvec3 t = s->entities.at(s->findByName("plain")).transform.translation;
    QVERIFY(std::abs(t.x - 500002.0) < 1e-6 && std::abs(t.y - 4400002.0) < 1e-6);
  }

  // ---- bad input: one line, the scene untouched --------------------------------------

  void badValuesAreRefusedInOneLine() {
    const QString f = newScene("refuse.hscene");
    expectRefused({"import", kBunny, f, "--decimate-to", "lots"}, 2, {"--decimate-to", "lots"}, f);
    expectRefused({"import", kBunny, f, "--decimate-to", "150%"}, 2, {"--decimate-to", "above 100%"}, f);
    expectRefused({"import", kBunny, f, "--max-error", "-1"}, 2, {"--max-error"}, f);
    expectRefused({"import", kBunny, f, "--max-error", "2cm"}, 2, {"--max-error", "metres"}, f);
    expectRefused({"import", kBunny, f, "--lods", "2.5"}, 2, {"--lods"}, f);
    expectRefused({"import", kBunny, f, "--lods", "99"}, 2, {"--lods", "0 to 8"}, f);
    expectRefused({"import", kBunny, f, "--origin", "north"}, 2, {"--origin"}, f);
    expectRefused({"import", kBunny, f, "--up", "x"}, 2, {"--up"}, f);
    expectRefused({"import", f}, 2, {"expected"}, f);
    // A tile that fails names itself; nothing is written.
    QFile bad(path("broken.obj"));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    bad.close();
    expectRefused({"import", kBunny, path("broken.obj"), f, "--decimate-to", "50%"}, 1, {"broken.obj:3:"}, f);
    expectRefused({"import", path("missing.obj"), f, "--lods", "2"}, 1, {"missing.obj"}, f);
  }

  // A file that crashes the reader (Assimp 5.2.5, double free): read in the
  // import worker, so the crash is one line naming the file, and the scene
  // stays byte for byte; the next import works.
  // mesh export through the real binary: a LOD level of an entity placed by
  // its transform, read back by Assimp (PLY) with the sidecar; refusals
  // name the problem, write nothing and leave the scene as it was.
  void exportALodLevel() {
    const QString f = newScene("export.hscene");
    Run r = cli({"import", kBunny, f, "--lods", "2", "--at", "500000,4400000,300"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const auto s = load(f);
    QVERIFY(s && s->assets.size() == 1);
    const scene::MeshAsset& asset = s->assets.begin()->second;
    QCOMPARE(asset.lods.size(), size_t(2));
    scene::EntityId entity = scene::kNoEntity;
    for (const auto& [id, e] : s->entities)
      if (e.mesh) entity = id;
    QVERIFY(entity != scene::kNoEntity);
    const QString name = QString::fromStdString(s->find(entity)->name);

    const QString out = path("lod1.ply");
    r = cli({"mesh", "export", f, name, out, "--lod", "1", "--up", "z"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("LOD 1"), qPrintable(r.out));
    mesh::ImportOptions io;
    io.up = mesh::UpAxis::Z;
    io.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Auto;
    const mesh::ImportResult back = mesh::importMesh(out.toStdString(), io);
    QVERIFY2(back.ok(), back.error.c_str());
    const mesh::MeshData& lod = *asset.lods[0].data;
    QCOMPARE(back.mesh->triangleCount(), lod.triangleCount());
    // Corner by corner where the entity puts it (float precision at 500 km).
    const glm::dmat4 m = s->worldMatrix(entity);
    double worst = 0.0;
    for (size_t c = 0; c < lod.indices.size(); ++c) {
      const glm::dvec3 want = glm::dvec3(m * glm::dvec4(lod.origin + glm::dvec3(lod.positions[lod.indices[c]]), 1.0));
      const glm::dvec3 got = back.mesh->origin + glm::dvec3(back.mesh->positions[back.mesh->indices[c]]);
      worst = std::max(worst, glm::length(got - want));
    }
    QVERIFY2(worst < 1e-5, qPrintable(QString("largest corner distance %1 m").arg(worst)));

    expectRefused({"mesh", "export", f, name, path("lod9.obj"), "--lod", "9"}, 1, {"--lod 9", "0 to 2"}, f);
    expectRefused({"mesh", "export", f, "Nothing", path("n.obj")}, 1, {"Nothing", QString::fromStdString(asset.name)}, f);
    expectRefused({"mesh", "export", f, name, path("x.stl")}, 1, {"x.stl", ".ply"}, f);
    expectRefused({"mesh", "export", f, name, path("x.obj"), "--lod", "40"}, 2, {"--lod"}, f);
    QVERIFY(!QFile::exists(path("lod9.obj")) && !QFile::exists(path("n.obj")) && !QFile::exists(path("x.obj")));
  }

  // PLY holds no materials: exporting a mesh with two says so on stderr
  // (the file is still written and the exit is 0); OBJ says nothing.
  void plyExportSaysWhatItDrops() {
    const QString obj = QString::fromStdString(test::writeTwoMaterialObj(tmp_.path().toStdString()));
    const QString f = newScene("two.hscene");
    Run r = cli({"import", obj, f, "--up", "z"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"mesh", "export", f, "two", path("two_out.ply")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.startsWith("warning: " + path("two_out.ply")) && r.err.contains("2 materials"), qPrintable(r.err));
    QVERIFY(QFile::exists(path("two_out.ply")));
    r = cli({"mesh", "export", f, "two", path("two_out.obj")});
    QVERIFY2(r.code == 0 && !r.err.contains("warning"), qPrintable(r.err));
  }

  void readerCrashIsOneLine() {
    const QString f = newScene("crash.hscene");
    const QString crashing = HS_TEST_DATA_DIR "/mesh/crashes_assimp_embedded_texture.fbx";
    expectRefused({"import", crashing, f}, 1,
                  {"crashes_assimp_embedded_texture.fbx: the FBX reader (Assimp) crashed on this file (SIGABRT)",
                   "Nothing was imported."},
                  f);
    expectRefused({"import", crashing, f, "--decimate-to", "50%", "--lods", "1"}, 1,
                  {"crashes_assimp_embedded_texture.fbx", "crashed"}, f);
    const Run ok = cli({"import", HS_TEST_DATA_DIR "/mesh/textured_quad.fbx", f});
    QVERIFY2(ok.code == 0, qPrintable(ok.err));
    QVERIFY2(ok.out.contains("reader assimp"), qPrintable(ok.out));
  }

  // Declared against imported (issue 10): a face with an index past the
  // vertices is dropped with a warning and the report holds both counts;
  // --strict refuses the import and leaves the scene as it was. A file cut
  // short read through the worker (ASCII STL) is refused either way.
  void strictRefusesWhatTheFileDeclaresButDidNotImport() {
    const QString f = newScene("strict.hscene");
    QString obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nf 1 2 9\n";
    writeFile(path("dropped.obj").toStdString(), obj.toStdString());
    const Run warned = cli({"import", path("dropped.obj"), f, "--report", path("dropped.json")});
    QVERIFY2(warned.code == 0, qPrintable(warned.err));
    QVERIFY2(warned.err.contains("declares 3 triangles") && warned.err.contains("2 were imported"), qPrintable(warned.err));
    const QJsonObject report = readReport(path("dropped.json"));
    QCOMPARE(report["declared"].toObject()["triangles"].toInt(), 3);
    QCOMPARE(report["triangles_out"].toInt(), 2);
    expectRefused({"import", path("dropped.obj"), f, "--strict"}, 1,
                  {"dropped.obj: the file declares 3 triangles", "2 were imported", "--strict"}, f);

    std::string stl = "solid cut\n";
    for (int i = 0; i < 20; ++i)
      stl += "facet normal 0 0 1\n outer loop\n  vertex 0 0 " + std::to_string(i) + "\n  vertex 1 0 " +
             std::to_string(i) + "\n  vertex 0 1 " + std::to_string(i) + "\n endloop\nendfacet\n";
    writeFile(path("cut.stl").toStdString(), stl);
    expectRefused({"import", path("cut.stl"), f}, 1, {"cut.stl: the ASCII STL is cut short", "20 complete facets"}, f);
  }
};

QTEST_GUILESS_MAIN(TestCliMesh)
#include "test_cli_mesh.moc"
