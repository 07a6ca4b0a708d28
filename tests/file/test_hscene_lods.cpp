// Mesh LODs and processing reports in the document and the .hscene file: an
// import with decimation and LODs carries them as one undo step, they round
// trip bit for bit as blobs of their own ("mesh/<id>/lod<k>") written only
// when changed, a damaged level is refused with a message naming the asset
// and the level, and files of formats 1 to 3 still open.
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "hscene_sql.h"
#include "scene/asset_reports.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene/import_pipeline.h"
#include "scene/mesh_report_text.h"
#include "scene/operations.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;
using hs::test::readBlob;
using hs::test::sql;
using hs::test::writeBlob;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

bool sameMesh(const mesh::MeshData& a, const mesh::MeshData& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return std::memcmp(&a.origin, &b.origin, sizeof a.origin) == 0 && same(a.positions, b.positions) &&
         same(a.normals, b.normals) && same(a.uvs, b.uvs) && same(a.indices, b.indices) &&
         a.submeshes.size() == b.submeshes.size() && a.materials.size() == b.materials.size();
}

// The bunny cleaned, decimated to half and given two coarser levels, as the
// Import dialog and `import --decimate-to 50% --lods 2` make it.
ImportedMesh decimatedBunny() {
  MeshImportRequest r;
  r.files = {kBunny};
  r.process = true;
  r.processing.decimate = true;
  r.processing.decimation.targetRatio = 0.5;
  r.processing.lodLevels = 2;
  r.processing.error.samplesPerFace = 2;  // quick; the numbers are not what is tested here
  return importMeshFiles(r);
}

}  // namespace

class TestHsceneLods : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  Document doc_;
  EntityId bunny_ = kNoEntity;

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }
  const MeshAsset& asset() const { return *doc_.state().findAsset(doc_.state().find(bunny_)->mesh->mesh); }

  // A saved copy of doc_ to damage.
  std::string saved(const std::string& name) {
    std::string error;
    const std::string p = path(name);
    if (!saveScene(doc_.state(), p, error)) qFatal("%s", error.c_str());
    return p;
  }
  void expectRefused(const std::string& file, const std::vector<std::string>& what) {
    std::string error;
    QVERIFY2(!loadScene(file, error), "a damaged file was opened");
    QVERIFY2(error.find(file) != std::string::npos, error.c_str());
    for (const auto& w : what)
      QVERIFY2(error.find(w) != std::string::npos, qPrintable(QString("'%1' not in: %2").arg(w.c_str(), error.c_str())));
    QVERIFY(error.find('\n') == std::string::npos);
    qInfo("refused as expected: %s", error.c_str());
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void importCarriesLodsAndReportInOneUndoStep() {
    doc_.reset(SceneState{}, {});
    ImportedMesh m = decimatedBunny();
    QVERIFY2(m.ok(), m.error.c_str());
    QVERIFY(m.processed);
    QCOMPARE(m.lods.size(), size_t(2));
    const size_t lod0 = m.mesh->triangleCount();
    QVERIFY(lod0 > 30000 && lod0 < 40000);  // half of 69,451
    bunny_ = ops::addImportedMesh(doc_, std::move(m), "bunny", kBunny);
    QVERIFY(bunny_ != kNoEntity);
    QCOMPARE(doc_.undoStack()->count(), 1);

    const MeshAsset& a = asset();
    QCOMPARE(a.lods.size(), size_t(2));
    // Each level about a quarter of the previous one, its error measured and
    // never below the previous level's.
    size_t previous = a.data->triangleCount();
    const std::vector<double> errors = a.lodErrors();
    QCOMPARE(errors.size(), size_t(3));
    QCOMPARE(errors[0], 0.0);
    for (size_t k = 0; k < a.lods.size(); ++k) {
      const size_t t = a.lods[k].data->triangleCount();
      QVERIFY(t < previous / 3 && t > previous / 5);
      QVERIFY(a.lods[k].hausdorff > 0 && a.lods[k].hausdorff >= errors[k]);
      QCOMPARE(a.lods[k].contentHash, mesh::contentHash(*a.lods[k].data));
      QVERIFY(a.lods[k].data->textures.empty());  // levels draw with level 0's
      previous = t;
    }
    // The report: cleaning counts, the decimation's error, per-level errors, times.
    const hs::Json& rep = a.processReport;
    QVERIFY(rep.value("cleaning", hs::Json()).is_object());
    QVERIFY(rep.value("decimation", hs::Json()).value("triangles_out", -1) == int(a.data->triangleCount()));
    const hs::Json e = rep.value("error", hs::Json());
    for (const char* key : {"hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "area_change_rel", "seconds"})
      QVERIFY2(e.value(key, hs::Json()).is_number(), key);
    QVERIFY(e.value("hausdorff_m", 0.0) > 0 && e.value("hausdorff_rel", 1.0) < 0.01);
    const hs::Json lods = rep.value("lods", hs::Json());
    QCOMPARE(lods.size(), size_t(3));
    for (size_t k = 1; k < 3; ++k)  // the double itself (numbers are written to read back exactly)
      QCOMPARE(lods[k].value("hausdorff_m", -1.0), a.lods[k - 1].hausdorff);
    QCOMPARE(rep.value("options", hs::Json()).value("lod_levels", -1), 2);
    // The levels' rate: the lower of the result's (2 here) and the levels' own.
    QCOMPARE(rep.value("options", hs::Json()).value("lod_samples_per_face", -1.0), 2.0);
    QCOMPARE(lods[1].value("samples_per_face", -1.0), 2.0);

    // Undo removes the entity, the asset and with it every level and the report.
    doc_.undoStack()->undo();
    QVERIFY(doc_.state().assets.empty());
    QVERIFY(doc_.state().entities.empty());
    doc_.undoStack()->redo();
    QCOMPARE(asset().lods.size(), size_t(2));
    QVERIFY(!asset().processReport.is_null());
  }

  void roundTripWithLodsAndReport() {
    const std::string p = path("lods.hscene");
    std::string error;
    SaveReport report;
    QVERIFY2(saveScene(doc_.state(), p, error, &report), error.c_str());
    QCOMPARE(report.blobsWritten, size_t(3));  // the mesh and its two levels
    QCOMPARE(readBlob(p, "mesh/1/lod1").empty(), false);
    QCOMPARE(readBlob(p, "mesh/1/lod2").empty(), false);
    QVERIFY(readBlob(p, "mesh/1/lod3").empty());
    QCOMPARE(sceneFileVersion(p), kSceneFormatVersion);

    const std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(canonicalJson(*back), canonicalJson(doc_.state()));
    const MeshAsset& a = asset();
    const MeshAsset& b = back->assets.begin()->second;
    QVERIFY(a == b);  // hashes, errors, reports
    QVERIFY(sameMesh(*a.data, *b.data));
    QCOMPARE(b.lods.size(), a.lods.size());
    for (size_t k = 0; k < a.lods.size(); ++k) {
      QVERIFY(sameMesh(*a.lods[k].data, *b.lods[k].data));
      QCOMPARE(b.lods[k].hausdorff, a.lods[k].hausdorff);  // the double itself
    }
    QVERIFY(b.processReport == a.processReport);
  }

  void lodBlobsAreWrittenOnlyWhenChanged() {
    const std::string p = path("incremental.hscene");
    std::string error;
    QVERIFY2(saveScene(doc_.state(), p, error), error.c_str());
    // An edit elsewhere: no blob is written.
    QVERIFY(ops::rename(doc_, bunny_, "bunny (renamed)"));
    SaveReport second;
    QVERIFY2(saveScene(doc_.state(), p, error, &second), error.c_str());
    QVERIFY(second.incremental);
    QCOMPARE(second.blobsWritten, size_t(0));
    QCOMPARE(second.blobsUnchanged, size_t(3));
    // The asset loses its coarsest level: that blob goes, nothing is written.
    {
      Edit e(doc_, "Drop a level");
      MeshAsset a = asset();
      a.lods.pop_back();
      e.addAsset(std::move(a));
      QVERIFY(e.commit());
    }
    SaveReport third;
    QVERIFY2(saveScene(doc_.state(), p, error, &third), error.c_str());
    QCOMPARE(third.blobsWritten, size_t(0));
    QCOMPARE(third.blobsRemoved, size_t(1));
    QVERIFY(readBlob(p, "mesh/1/lod2").empty());
    const std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->assets.begin()->second.lods.size(), size_t(1));
    // Undo brings it back; the next save writes that one level.
    doc_.undoStack()->undo();
    doc_.undoStack()->undo();
    SaveReport fourth;
    QVERIFY2(saveScene(doc_.state(), p, error, &fourth), error.c_str());
    QCOMPARE(fourth.blobsWritten, size_t(1));
    QCOMPARE(asset().lods.size(), size_t(2));
  }

  // ---- damaged levels: refused, naming the asset and the level ------------------

  void lodBlobChecksumMismatch() {
    const std::string p = saved("lodhash.hscene");
    std::vector<uint8_t> blob = readBlob(p, "mesh/1/lod2");
    QVERIFY(blob.size() > 1000);
    blob[100] ^= 0x01;  // inside the positions: still a mesh, not the one hashed
    writeBlob(p, "mesh/1/lod2", blob);
    expectRefused(p, {"mesh asset 1 ('bunny')", "LOD 2", "checksum"});
  }

  void truncatedLodBlob() {
    const std::string p = saved("lodcut.hscene");
    std::vector<uint8_t> blob = readBlob(p, "mesh/1/lod1");
    blob.resize(blob.size() / 2);
    writeBlob(p, "mesh/1/lod1", blob);
    expectRefused(p, {"mesh asset 1", "LOD 1", "truncated"});
  }

  void missingLodBlob() {
    const std::string p = saved("lodgone.hscene");
    sql(p, "DELETE FROM blobs WHERE key = 'mesh/1/lod1'");
    expectRefused(p, {"mesh asset 1", "LOD 1", "missing"});
  }

  void lodErrorsThatShrinkAreRefused() {
    const std::string p = saved("lodorder.hscene");
    sql(p, "UPDATE document SET json = json_set(json, '$.assets[0].lods[1].hausdorff_m', 0) WHERE id = 1");
    expectRefused(p, {"assets[0].lods[1].hausdorff_m", "must not decrease"});
  }

  // ---- older formats ------------------------------------------------------------------

  void formatsOneAndTwoStillOpen_data() {
    QTest::addColumn<int>("version");
    QTest::newRow("format 1") << 1;
    QTest::newRow("format 2") << 2;
  }
  void formatsOneAndTwoStillOpen() {
    QFETCH(int, version);
    // What an older build wrote: meshes without levels, reports or the LOD
    // setting, under its own version number. The file is a real one of an
    // older build (tests/data/file/README.md), so its blobs carry the hashes
    // of their time.
    const std::string p = path("old" + std::to_string(version) + ".hscene");
    fs::copy_file(HS_TEST_DATA_DIR "/file/format3_plain.hscene", p, fs::copy_options::overwrite_existing);
    std::string error;
    sql(p, "UPDATE meta SET value = '" + std::to_string(version) + "' WHERE key = 'format_version'");
    sql(p, "UPDATE document SET json = json_remove(json, '$.settings.mesh_lod_error_px') WHERE id = 1");
    QCOMPARE(sceneFileVersion(p), version);

    std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->assets.size(), size_t(1));
    QVERIFY(back->assets.begin()->second.lods.empty());
    QVERIFY(back->assets.begin()->second.processReport.is_null());
    QCOMPARE(back->settings.meshLodErrorPixels, 1.0);  // the default
    // Saving over it writes the current format (a whole new file: an older
    // build must not half-understand it).
    SaveReport report;
    QVERIFY2(saveScene(*back, p, error, &report), error.c_str());
    QVERIFY(!report.incremental);
    QCOMPARE(sceneFileVersion(p), kSceneFormatVersion);
    QVERIFY(loadScene(p, error));
  }

  // A real format-3 file (tests/data/file/README.md: a decimated mesh with a
  // LOD level, a painted terrain, keys): it opens, every blob checked against
  // the hash that file holds, and is saved whole in the current format.
  void format3FromAnOlderBuildOpens() {
    const std::string p = path("format3.hscene");
    fs::copy_file(HS_TEST_DATA_DIR "/file/format3.hscene", p, fs::copy_options::overwrite_existing);
    QCOMPARE(sceneFileVersion(p), 3);
    std::string error;
    const std::optional<SceneState> first = loadScene(p, error);
    QVERIFY2(first, error.c_str());
    QCOMPARE(first->assets.size(), size_t(1));
    const MeshAsset& a = first->assets.begin()->second;
    QCOMPARE(a.data->triangleCount(), size_t(760));
    QCOMPARE(a.lods.size(), size_t(1));
    QCOMPARE(a.lods[0].data->triangleCount(), size_t(198));
    QCOMPARE(a.contentHash, mesh::contentHash(*a.data));  // the document holds the current hash
    QCOMPARE(first->terrains.size(), size_t(1));
    const terrain::Terrain& t = first->terrains.begin()->second.data->terrain();
    QCOMPARE(t.height.samplesX(), 129);
    // Painted: somewhere a layer other than the base holds weight.
    bool painted = false;
    for (int y = 0; y < 129 && !painted; y += 8)
      for (int x = 0; x < 129 && !painted; x += 8) painted = t.paint.weight(0, x, y) < 1.0f;
    QVERIFY(painted);
    QCOMPARE(first->sequence.bindings.size(), size_t(1));

    SaveReport report;
    QVERIFY2(saveScene(*first, p, error, &report), error.c_str());
    QVERIFY(!report.incremental);
    QCOMPARE(sceneFileVersion(p), kSceneFormatVersion);
    const std::optional<SceneState> again = loadScene(p, error);
    QVERIFY2(again, error.c_str());
    QCOMPARE(canonicalJson(*again), canonicalJson(*first));
  }

  // The reports of a format-3 file (written by Qt's JSON: sorted keys, nine
  // significant digits) read through the readers and come back in the
  // current form, which then round-trips byte for byte.
  void format3ReportsReadBack() {
    const std::string p = path("format3-reports.hscene");
    fs::copy_file(HS_TEST_DATA_DIR "/file/format3.hscene", p, fs::copy_options::overwrite_existing);
    std::string error;
    const std::optional<SceneState> first = loadScene(p, error);
    QVERIFY2(first, error.c_str());
    const MeshAsset& a = first->assets.begin()->second;
    // What the fixture says (tests/data/file/README.md: 50% of 1600, two
    // levels asked, one kept).
    const std::optional<AssetProcessReport> report = readProcessReport(a.processReport);
    QVERIFY(report);
    QVERIFY(report->report.decimated && report->report.cleaned && report->report.errorMeasured);
    QCOMPARE(report->report.decimation.trianglesOut, size_t(760));
    QCOMPARE(report->report.cleaning.zeroAreaFaces, size_t(80));
    QCOMPARE(report->report.error.hausdorff, 0.0170768261);
    QCOMPARE(report->report.lods.size(), size_t(2));
    QCOMPARE(report->options.lodLevels, 2);
    QCOMPARE(report->options.decimation.targetRatio, 0.5);
    QVERIFY(std::isinf(report->options.decimation.maxError));  // null: no bound
    // Before the levels had a rate of their own they were measured at the
    // result's, which is what the report then says.
    QCOMPARE(report->options.lodSamplesPerFace, report->options.error.samplesPerFace);
    QCOMPARE(a.importReport.at("triangles_in").get<int>(), 1600);
    QCOMPARE(a.importReport.at("skipped_primitives").get<int>(), 0);
    for (const Json* r : {&a.importReport, &a.processReport}) {
      const std::string text = writeJson(*r);
      JsonReader reader(error);
      AssetProcessReport p2;
      AssetImportReport i2;
      const std::optional<Json> j = parseJson(text, error);
      QVERIFY2(j, error.c_str());
      QVERIFY2(r == &a.processReport ? fromJson(reader, *j, "", p2) : fromJson(reader, *j, "", i2), error.c_str());
      QCOMPARE(writeJson(r == &a.processReport ? toJson(p2) : toJson(i2)), text);
    }
  }

  // A report written before "skipped_primitives" says "skipped_lines": it
  // is read, and saved under the current key. A report member of the wrong
  // type refuses the file, naming its path.
  void oldReportKeysAndBadReports() {
    const std::string p = path("format3-old-key.hscene");
    fs::copy_file(HS_TEST_DATA_DIR "/file/format3_plain.hscene", p, fs::copy_options::overwrite_existing);
    sql(p, "UPDATE document SET json = json_set(json_remove(json, '$.assets[0].import_report.skipped_primitives'), "
           "'$.assets[0].import_report.skipped_lines', 12) WHERE id = 1");
    std::string error;
    const std::optional<SceneState> s = loadScene(p, error);
    QVERIFY2(s, error.c_str());
    const Json& report = s->assets.begin()->second.importReport;
    QCOMPARE(report.at("skipped_primitives").get<int>(), 12);
    QVERIFY(!report.contains("skipped_lines"));

    const std::string q = path("format3-bad-report.hscene");
    fs::copy_file(HS_TEST_DATA_DIR "/file/format3.hscene", q, fs::copy_options::overwrite_existing);
    sql(q, "UPDATE document SET json = json_set(json, '$.assets[0].process_report.error.hausdorff_m', 'small') "
           "WHERE id = 1");
    expectRefused(q, {"assets[0].process_report.error.hausdorff_m (line 1, column ", "expected a number, not a string"});
  }

  // The reports an asset keeps, with tiles and options: write, read, write
  // gives the same bytes.
  void assetReportsRoundTrip() {
    AssetProcessReport p;
    p.report.cleaned = true;
    p.report.cleaning.trianglesIn = 1000;
    p.report.cleaning.warnings = {"2 faces have zero area and were removed"};
    p.report.lods = {{1000, 0.0, 0.0, 0.25}, {250, 0.0123456789, 1.0 / 3.0, 0.125}};
    p.report.seconds = 0.1 + 0.2;
    p.options.decimate = true;
    p.options.decimation.targetTriangles = 500000;
    p.options.decimation.maxError = 0.02;
    p.options.lodLevels = 3;
    p.tiles = TileWeldReport{2, 1e-3, 41, 20, 21};
    AssetImportReport i;
    i.report.file = "a.obj";
    i.report.trianglesIn = 10;
    i.tiles = {i.report, i.report};
    i.tiles[1].file = "b.obj";
    std::string error;
    JsonReader reader(error);
    AssetProcessReport p2;
    AssetImportReport i2;
    const std::string pt = writeJson(toJson(p)), it = writeJson(toJson(i));
    QVERIFY2(fromJson(reader, *parseJson(pt, error), "", p2), error.c_str());
    QVERIFY2(fromJson(reader, *parseJson(it, error), "", i2), error.c_str());
    QCOMPARE(writeJson(toJson(p2)), pt);
    QCOMPARE(writeJson(toJson(i2)), it);
    QCOMPARE(p2.options.decimation.targetTriangles, size_t(500000));
    QCOMPARE(p2.options.decimation.maxError, 0.02);
    QVERIFY(p2.tiles && p2.tiles->borderVerticesMerged == 21);
    QCOMPARE(i2.tiles.size(), size_t(2));
    QCOMPARE(i2.tiles[1].file, std::string("b.obj"));
  }

  // A maximum error no decimation run met is said, in the report's rows
  // and as a warning (the editor's Messages, the CLI's stderr); whether it
  // was met follows from the stored options and the measured error, so
  // reports saved before this say it too.
  void anUnmetMaximumErrorIsSaid() {
    AssetProcessReport p;
    p.report.decimated = true;
    p.report.decimation.trianglesIn = 1000;
    p.report.decimation.trianglesOut = 120;
    p.report.maxErrorPasses = 4;
    p.report.errorMeasured = true;
    p.report.error.hausdorff = 0.031;
    p.options.decimate = true;
    p.options.decimation.maxError = 0.02;
    auto row = [](const Json& report) {
      for (const ReportSection& s : processReportSections(report))
        for (const ReportRow& r : s.rows)
          if (r.key == "max_error_m") return r.value;
      return std::string();
    };
    std::vector<std::string> w = processWarnings(toJson(p));
    QCOMPARE(w.size(), size_t(1));
    QVERIFY2(w[0].find("0.02 m") != std::string::npos && w[0].find("0.031 m") != std::string::npos &&
                 w[0].find("4 decimation runs") != std::string::npos,
             w[0].c_str());
    QVERIFY2(row(toJson(p)).find("NOT met") != std::string::npos, row(toJson(p)).c_str());
    p.report.error.hausdorff = 0.015;
    QVERIFY(processWarnings(toJson(p)).empty());
    QVERIFY2(row(toJson(p)).find("(met)") != std::string::npos, row(toJson(p)).c_str());
    p.options.decimation.maxError = std::numeric_limits<double>::infinity();  // a triangle target only
    p.report.error.hausdorff = 0.031;
    QVERIFY(processWarnings(toJson(p)).empty());
    QVERIFY(row(toJson(p)).empty());
  }

  // The old hashes are really checked: a changed byte in a format-3 file's
  // mesh or terrain tile is refused.
  void format3DamageIsRefused() {
    for (const std::string key : {"mesh/1", "mesh/1/lod1", "terrain/1/h/0_0"}) {
      const std::string p = path("format3-damaged.hscene");
      fs::copy_file(HS_TEST_DATA_DIR "/file/format3.hscene", p, fs::copy_options::overwrite_existing);
      std::vector<uint8_t> bytes = readBlob(p, key);
      QVERIFY2(bytes.size() > 200, key.c_str());
      bytes[bytes.size() - 100] ^= 0x01;  // inside the data, past every header
      writeBlob(p, key, bytes);
      std::string error;
      QVERIFY2(!loadScene(p, error), key.c_str());
      QVERIFY2(error.find("checksum") != std::string::npos || error.find("damaged") != std::string::npos,
               error.c_str());
    }
  }

  void lodSettingIsSaved() {
    Document d;
    d.reset(SceneState{}, {});
    QVERIFY(ops::setSettingsField(d, *findSettingsField("mesh_lod_error_px"), 2.5));
    QCOMPARE(d.state().settings.meshLodErrorPixels, 2.5);
    const std::string p = path("setting.hscene");
    std::string error;
    QVERIFY2(saveScene(d.state(), p, error), error.c_str());
    const std::optional<SceneState> back = loadScene(p, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->settings.meshLodErrorPixels, 2.5);
    // Clamped to its range like every field.
    QVERIFY(ops::setSettingsField(d, *findSettingsField("mesh_lod_error_px"), -3.0));
    QCOMPARE(d.state().settings.meshLodErrorPixels, 0.0);
  }
};

QTEST_GUILESS_MAIN(TestHsceneLods)
#include "test_hscene_lods.moc"
