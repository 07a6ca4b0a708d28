// The error report: zero for identical meshes, exact for a known offset
// (also at UTM coordinates), every field in the JSON, non-manifold counts.
#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/mesh_process.h"
#include "meshproc/report_json.h"
#include "mesh_builders.h"

using namespace hs::mesh;
using hs::test::curvedGrid;

class TestMeshprocError : public QObject {
  Q_OBJECT

 private slots:
  void identicalMeshesMeasureZero() {
    const MeshData m = curvedGrid(30, 5.0, 0.3, true);
    ErrorOptions o;
    o.textureWidth = o.textureHeight = 512;
    const ErrorReport e = measureError(m, m, o);
    QCOMPARE(e.hausdorff, 0.0);
    QCOMPARE(e.mean, 0.0);
    QCOMPARE(e.rms, 0.0);
    QCOMPARE(e.p95, 0.0);
    QCOMPARE(e.flippedNormals, size_t(0));
    QCOMPARE(e.constrainedVerticesMoved, size_t(0));
    QVERIFY(e.uvMeasured);
    QVERIFY(e.uvMaxTexels < 1e-3);
    QCOMPARE(e.areaOut, e.areaIn);
    // 10 samples per face by default, in each direction.
    QCOMPARE(e.forward.samples, uint64_t(10 * m.triangleCount()));
    QCOMPARE(e.backward.samples, uint64_t(10 * m.triangleCount()));
  }

  void planeMovedByDMeasuresD_data() {
    QTest::addColumn<double>("d");
    QTest::addColumn<bool>("utm");
    QTest::newRow("1 cm") << 0.01 << false;
    QTest::newRow("0.37 m") << 0.37 << false;
    QTest::newRow("1 cm at UTM") << 0.01 << true;
  }
  void planeMovedByDMeasuresD() {
    QFETCH(double, d);
    QFETCH(bool, utm);
    MeshData a = curvedGrid(20, 8.0, 0.0, false);
    MeshData b = a;
    const glm::dvec3 base = utm ? glm::dvec3(656059.0, 5514553.0, 1713.0) : glm::dvec3(0.0);
    a.origin = base;
    b.origin = base + glm::dvec3(0.0, 0.0, d);  // the same plane, d higher (in double)
    const ErrorReport e = measureError(a, b);
    QVERIFY2(std::abs(e.hausdorff - d) <= 1e-9 * d, qPrintable(QString("%1 vs %2").arg(e.hausdorff, 0, 'g', 17).arg(d)));
    QVERIFY(std::abs(e.mean - d) <= 1e-6 * d);
    QVERIFY(std::abs(e.p95 - d) <= 1e-6 * d);
    QVERIFY(std::abs(e.forward.max - d) <= 1e-9 * d);
    QVERIFY(std::abs(e.backward.max - d) <= 1e-9 * d);
    QVERIFY(std::abs(e.rel(e.hausdorff) - d / (8.0 * std::sqrt(2.0))) < 1e-9);
  }

  void reportJsonHasPlainFields() {
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.5;
    o.error.textureWidth = o.error.textureHeight = 256;
    o.lodLevels = 2;
    ProcessResult r = processMesh(curvedGrid(40, 10.0, 0.5, true), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.lods.size(), size_t(2));
    const std::string json = processReportJson(r.report);
    QJsonParseError perr;
    const QJsonDocument doc = QJsonDocument::fromJson(QByteArray::fromStdString(json), &perr);
    QVERIFY2(perr.error == QJsonParseError::NoError, qPrintable(perr.errorString()));
    const QJsonObject root = doc.object();
    const QJsonObject err = root["error"].toObject();
    for (const char* k : {"hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "flipped_normals",
                          "boundary_seam_vertices_moved", "area_in_m2", "area_out_m2", "volume_in_m3",
                          "non_manifold_edges_in", "non_manifold_edges_out", "seconds", "samples_per_face"})
      QVERIFY2(err.contains(k), k);
    QVERIFY(err["hausdorff_m"].toDouble() > 0);
    const double rel = err["hausdorff_m"].toDouble() / err["bbox_diagonal_m"].toDouble();
    QVERIFY(std::abs(err["hausdorff_rel"].toDouble() - rel) <= 1e-8 * rel);  // 9 digits in the file
    QVERIFY(err["uv_displacement_texels"].toObject().contains("p95"));
    const QJsonObject dec = root["decimation"].toObject();
    QCOMPARE(dec["triangles_out"].toInt(), int(r.mesh.triangleCount()));
    QVERIFY(dec.contains("seconds"));
    QCOMPARE(root["lods"].toArray().size(), 3);
    QVERIFY(root["lods"].toArray()[2].toObject()["hausdorff_m"].toDouble() >=
            root["lods"].toArray()[1].toObject()["hausdorff_m"].toDouble());
    QVERIFY(root["cleaning"].toObject().contains("duplicate_vertices_welded"));
  }

  // Maximum error in metres is met as measured, not only as estimated.
  void maxErrorIsMetAsMeasured() {
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.0;
    o.decimation.maxError = 0.01;
    ProcessResult r = processMesh(curvedGrid(60, 10.0, 0.8, false), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.errorMeasured);
    QVERIFY2(r.report.error.hausdorff <= 0.01, qPrintable(QString::number(r.report.error.hausdorff)));
    QVERIFY(r.mesh.triangleCount() < 60 * 60 * 2 / 4);
    QVERIFY(r.report.maxErrorPasses >= 1);
  }

  void nonManifoldCountsInAndOut() {
    // Two triangles sharing one corner only (a bow-tie) and three faces on one edge.
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0},
                   {5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {5, -1, 0}, {5, 0, 1}};
    m.indices = {0, 1, 2, 0, 3, 4, 5, 6, 7, 6, 5, 8, 5, 6, 9};
    const NonManifoldCounts c = countNonManifold(m);
    QCOMPARE(c.vertices, size_t(1));
    QCOMPARE(c.edges, size_t(1));
  }
};

QTEST_GUILESS_MAIN(TestMeshprocError)
#include "test_meshproc_error.moc"
