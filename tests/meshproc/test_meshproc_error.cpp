// The error report: zero for identical meshes, exact for a known offset
// (also at UTM coordinates), every field in the JSON, the reports' JSON
// round trips byte for byte, non-manifold counts.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/mesh_process.h"
#include "meshproc/report_json.h"
#include "defect_cases.h"
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
    // The certified bound: every point is d from the other plane; the
    // bound comes within its slack (1%) of that, never below it.
    const HausdorffBound h = ErrorMeter(a).hausdorffUpperBound(b, e.hausdorff);
    QVERIFY2(h.upper >= d * (1 - 1e-12) && h.upper <= 1.01 * d,
             qPrintable(QString("%1 vs %2").arg(h.upper, 0, 'g', 17).arg(d)));
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
    const std::string json = hs::writeJson(toJson(r.report));
    std::string perr;
    const std::optional<hs::Json> doc = hs::parseJson(json, perr);  // strict: the text is JSON
    QVERIFY2(doc, perr.c_str());
    const hs::Json& root = *doc;
    const hs::Json& err = root.at("error");
    for (const char* k : {"hausdorff_m", "hausdorff_rel", "mean_m", "rms_m", "p95_m", "flipped_normals",
                          "boundary_seam_vertices_moved", "area_in_m2", "area_out_m2", "volume_in_m3",
                          "non_manifold_edges_in", "non_manifold_edges_out", "seconds", "samples_per_face"})
      QVERIFY2(err.contains(k), k);
    QVERIFY(err.at("hausdorff_m").get<double>() > 0);
    // Numbers read back to the same doubles, so the relative error is the
    // quotient of the two numbers in the file, exactly.
    QCOMPARE(err.at("hausdorff_rel").get<double>(),
             err.at("hausdorff_m").get<double>() / err.at("bbox_diagonal_m").get<double>());
    QVERIFY(err.at("uv_displacement_texels").contains("p95"));
    const hs::Json& dec = root.at("decimation");
    QCOMPARE(dec.at("triangles_out").get<size_t>(), r.mesh.triangleCount());
    QVERIFY(dec.contains("seconds"));
    QCOMPARE(root.at("lods").size(), size_t(3));
    QVERIFY(root.at("lods")[2].at("hausdorff_m").get<double>() >= root.at("lods")[1].at("hausdorff_m").get<double>());
    // The result's report at its rate, the levels at theirs (level 0 is
    // the result itself: nothing measured).
    QCOMPARE(err.at("samples_per_face").get<double>(), o.error.samplesPerFace);
    QCOMPARE(root.at("lods")[0].at("samples_per_face").get<double>(), 0.0);
    for (size_t level : {1u, 2u}) {
      const double rate = root.at("lods")[level].at("samples_per_face").get<double>();
      // Each level's samples are whole numbers over the result's faces.
      QVERIFY2(std::abs(rate - o.lodSamplesPerFace) < 1e-9, qPrintable(QString::number(rate)));
    }
    QVERIFY(root.at("cleaning").contains("duplicate_vertices_welded"));
  }

  // Write, read, write gives the same bytes, for a processing report with
  // every section and for import reports with awkward numbers; what is read
  // is the value that was written (NaN comes back for what was not finite).
  void reportsRoundTripByteForByte() {
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.3;
    o.error.textureWidth = o.error.textureHeight = 300;
    o.lodLevels = 2;
    ProcessResult r = processMesh(curvedGrid(30, 7.0, 0.4, true), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.cleaned && r.report.decimated && r.report.errorMeasured && r.report.error.uvMeasured);
    const std::string text = hs::writeJson(toJson(r.report));
    std::string error;
    const std::optional<hs::Json> doc = hs::parseJson(text, error);
    QVERIFY2(doc, error.c_str());
    hs::JsonReader reader(error);
    ProcessReport back;
    QVERIFY2(fromJson(reader, *doc, "", back), error.c_str());
    QCOMPARE(hs::writeJson(toJson(back)), text);
    QCOMPARE(back.error.hausdorff, r.report.error.hausdorff);
    QCOMPARE(back.error.forward.p95, r.report.error.forward.p95);
    QCOMPARE(back.error.seed, r.report.error.seed);
    QCOMPARE(back.decimation.secondsTotal, r.report.decimation.secondsTotal);
    QCOMPARE(back.cleaning.degenerateFaceIndices, r.report.cleaning.degenerateFaceIndices);
    QCOMPARE(back.lods.size(), r.report.lods.size());
    QCOMPARE(back.lods.back().hausdorffRel, r.report.lods.back().hausdorffRel);
    QCOMPARE(back.maxErrorPasses, r.report.maxErrorPasses);
    QVERIFY(r.report.refined && back.refined);
    QCOMPARE(back.refinement.moved, r.report.refinement.moved);
    QCOMPARE(back.refinement.largestAfter, r.report.refinement.largestAfter);

    ImportReport in;
    in.file = "scan \"7\"\n\xc3\xa9.obj";
    in.reader = "obj";
    in.verticesIn = 4000000000ull;
    in.trianglesOut = 123456789;
    in.skippedLines = 7;
    in.warnings = {"scan.obj:3: a line", "scan.obj:9: another"};
    in.seconds = 1.0 / 3.0;
    in.geoOffset = {512345.123456789, 4412345.987654321, 0.1};
    in.geoOffsetSource = "scan_offset.xyz";
    in.geoOffsetCrs = "EPSG:32634";
    ImportReport plain;
    plain.seconds = std::numeric_limits<double>::infinity();  // written as null
    for (const ImportReport& report : {in, plain}) {
      const std::string t = hs::writeJson(toJson(report));
      const std::optional<hs::Json> j = hs::parseJson(t, error);
      QVERIFY2(j, error.c_str());
      ImportReport b;
      QVERIFY2(fromJson(reader, *j, "", b), error.c_str());
      QCOMPARE(hs::writeJson(toJson(b)), t);
      QCOMPARE(b.file, report.file);
      QCOMPARE(b.verticesIn, report.verticesIn);
      QCOMPARE(b.skippedLines, report.skippedLines);
      QCOMPARE(b.warnings, report.warnings);
      QCOMPARE(b.geoOffset, report.geoOffset);
      QCOMPARE(b.geoOffsetSource, report.geoOffsetSource);
      QVERIFY(std::isfinite(report.seconds) ? b.seconds == report.seconds : std::isnan(b.seconds));
    }
  }

  // The decimation's schedule (rounds, levels, the last region's share) is
  // in the report; the last region's time was "seconds_border_pass" before
  // region levels replaced that pass, and that key is still read.
  void decimationReportKeys() {
    DecimateOptions o;
    o.targetRatio = 0.2;
    o.facesPerRegion = 8000;  // 10 regions on an 80,000-face grid: levels run above their floors
    const DecimateResult r = decimate(curvedGrid(200, 7.0, 0.4, false), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.regions > 1 && r.report.rounds > 0 && r.report.levels > 0);
    const hs::Json j = toJson(r.report);
    QCOMPARE(j.at("rounds").get<unsigned>(), r.report.rounds);
    QCOMPARE(j.at("levels").get<unsigned>(), r.report.levels);
    QCOMPARE(j.at("last_region_collapses").get<size_t>(), r.report.lastRegionCollapses);
    QVERIFY(j.contains("seconds_last_region") && !j.contains("seconds_border_pass"));
    std::string error;
    hs::JsonReader reader(error);
    const std::optional<hs::Json> old =
        hs::parseJson(R"({"decimation": {"collapses": 9, "seconds_border_pass": 0.25}})", error);
    QVERIFY2(old, error.c_str());
    ProcessReport p;
    QVERIFY2(fromJson(reader, *old, "process_report", p), error.c_str());
    QCOMPARE(p.decimation.collapses, size_t(9));
    QCOMPARE(p.decimation.secondsLastRegion, 0.25);
    const std::optional<hs::Json> bad = hs::parseJson(R"({"decimation": {"seconds_border_pass": "slow"}})", error);
    QVERIFY2(bad, error.c_str());
    QVERIFY(!fromJson(reader, *bad, "process_report", p));
    QVERIFY2(error.find("process_report.decimation.seconds_border_pass") == 0, error.c_str());
  }

  // One key for primitives no triangle came from; reports written before it
  // say "skipped_lines", which is still read. A member of the wrong type is
  // refused with its path.
  void importReportKeys() {
    ImportReport in;
    in.skippedLines = 5;
    const hs::Json j = toJson(in);
    QCOMPARE(j.at("skipped_primitives").get<size_t>(), size_t(5));
    QVERIFY(!j.contains("skipped_lines"));
    std::string error;
    hs::JsonReader reader(error);
    const std::optional<hs::Json> old = hs::parseJson(R"({"file": "a.obj", "skipped_lines": 12, "seconds": 0.5})", error);
    QVERIFY2(old, error.c_str());
    ImportReport b;
    QVERIFY2(fromJson(reader, *old, "import_report", b), error.c_str());
    QCOMPARE(b.skippedLines, size_t(12));
    QCOMPARE(b.file, std::string("a.obj"));
    QVERIFY(hs::writeJson(toJson(b), -1).find("\"skipped_primitives\":12") != std::string::npos);
    const std::optional<hs::Json> bad = hs::parseJson(R"({"cleaning": {"triangles_in": "many"}})", error);
    QVERIFY2(bad, error.c_str());
    ProcessReport p;
    QVERIFY(!fromJson(reader, *bad, "process_report", p));
    QCOMPARE(error, std::string("process_report.cleaning.triangles_in: expected a whole number from 0 to "
                                "9223372036854775807, not a string"));
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

  // The estimate can understate one feature's distance several times (a
  // fin, a loose flap): runs then measured about the same maximum while
  // the estimate shrank by 10% a run, and 3 of these 40 random defect
  // meshes were still above the bound after the runs allowed. A run that
  // comes no closer now halves the estimate. And when no run meets it,
  // the run measured closest is kept, never one further than the first.
  void maxErrorIsMetOnMeshesWithDefects() {
    std::mt19937 rng(5);
    int retried = 0;
    for (int trial = 0; trial < 40; ++trial) {
      const int n = 10 + int(rng() % 40);
      const double amplitude = 0.3 * double(rng() % 3);
      const MeshData grid = curvedGrid(n, 10.0, amplitude, rng() % 2 == 0);
      MeshData in = grid;
      const int defects = int(rng() % 12);
      for (int d = 0; d < defects; ++d) hs::test::addDefect(in, grid, int(rng() % 8), rng);
      ProcessOptions o;
      o.decimate = true;
      o.decimation.targetRatio = 0;
      o.decimation.maxError = 0.05;
      o.decimation.facesPerRegion = 1000;
      o.error.samplesPerFace = 2;
      const ProcessResult r = processMesh(in, o);
      const QString where = QString("trial %1: hausdorff %2 after %3 runs")
                                .arg(trial)
                                .arg(r.report.error.hausdorff)
                                .arg(r.report.maxErrorPasses);
      QVERIFY2(r.ok(), r.error.c_str());
      QVERIFY2(r.report.errorMeasured && r.report.error.hausdorff <= 0.05, qPrintable(where));
      retried += r.report.maxErrorPasses > 1;
      if (r.report.maxErrorPasses > 1) {
        ProcessOptions once = o;
        once.maxErrorRetries = 0;
        const ProcessResult first = processMesh(in, once);
        QVERIFY2(first.report.error.hausdorff > 0.05, qPrintable(where));  // it needed the retries
        ProcessOptions two = o;
        two.maxErrorRetries = 1;
        const ProcessResult r2 = processMesh(in, two);
        QVERIFY2(r2.report.error.hausdorff <= first.report.error.hausdorff, qPrintable(where));
      }
    }
    QVERIFY2(retried >= 10, qPrintable(QString::number(retried)));  // 23 of 40 take more than one run
  }

  // A face stored again the other way round glues itself to its own
  // border edges: in the input's topology the corner of a grid whose one
  // face has such a copy is no border vertex. The result (the copy gone,
  // the corner where it was) is on the input's border all the same, and
  // the report must not count its corner as moved; a corner that did move
  // still counts. Found by meshproc_defect_campaign (5 of 6,000 cases).
  void aReversedCopyOfACornerFaceIsNoMovedCorner() {
    const int n = 12;
    const MeshData grid = curvedGrid(n, 10.0, 0.3, false);
    const size_t f = size_t(2 * (n - 1));  // the only face at the corner (n, 0)
    const uint32_t a = grid.indices[f * 3], b = grid.indices[f * 3 + 1], c = grid.indices[f * 3 + 2];
    QCOMPARE(grid.positions[b], glm::vec3(10.0f, 0.0f, grid.positions[b].z));  // the corner is b
    MeshData in = grid;
    in.indices.insert(in.indices.end(), {a, c, b});
    in.submeshes.back().indexCount = uint32_t(in.indices.size());

    const ErrorReport same = measureError(in, grid);
    QVERIFY(same.constrainedVerticesOut >= size_t(4 * n));
    QCOMPARE(same.constrainedVerticesMoved, size_t(0));

    MeshData moved = grid;
    moved.positions[b].x += 0.3f;  // off the border, outwards
    const ErrorReport off = measureError(in, moved);
    QCOMPARE(off.constrainedVerticesMoved, size_t(1));
    QVERIFY(std::abs(off.constrainedMaxDeviation - 0.3) < 1e-4);

    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.02;
    o.decimation.facesPerRegion = 100;
    const ProcessResult r = processMesh(in, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.errorMeasured);
    QCOMPARE(r.report.error.constrainedVerticesMoved, size_t(0));
  }

  // The cases meshproc_defect_campaign found failing at stop 29 (seeds 1-3,
  // 2,000 trials each), replayed with the campaign's own checks: ten
  // maximum errors still over the bound after the 3 retries allowed then
  // (0-13% over; 6 retries meet all of them, in at most 5 runs) and five
  // corners counted as moved because of a face's reversed copy.
  void campaignCasesThatOnceFailedPass() {
    const std::vector<std::pair<unsigned, std::vector<int>>> found = {
        {1, {82, 179, 195, 852, 1196, 1682}}, {2, {96, 401, 707, 1193, 1258, 1836}}, {3, {528, 1717, 1991}}};
    int maxErrorCases = 0;
    for (const auto& [seed, trials] : found) {
      hs::test::DefectCases cases(seed);
      for (int trial = 0; trial <= trials.back(); ++trial) {
        const hs::test::DefectCase c = cases.next();
        if (std::find(trials.begin(), trials.end(), trial) == trials.end()) continue;
        // As found (without the vertex refinement, which came later and
        // lets some of them meet the bound at the first run), and as an
        // import runs them now.
        hs::test::DefectCase plain = c;
        plain.options.refine = false;
        const hs::test::DefectOutcome r = hs::test::checkDefectCase(plain);
        const std::string what = c.where + ": " + (r.failures.empty() ? "" : r.failures[0]);
        QVERIFY2(r.failures.empty(), what.c_str());
        if (c.target == 3) {
          ++maxErrorCases;
          QVERIFY2(r.runs >= 2, c.where.c_str());  // each needed reruns; none met the bound at once
        }
        const hs::test::DefectOutcome refined = hs::test::checkDefectCase(c);
        const std::string whatRefined = c.where + " (refined): " + (refined.failures.empty() ? "" : refined.failures[0]);
        QVERIFY2(refined.failures.empty(), whatRefined.c_str());
      }
    }
    QCOMPARE(maxErrorCases, 11);  // the ten, and one of the two corners (seed 1 trial 195)
  }

  // checkVertices, which lets a maximum-error run over its bound be rerun
  // without the full measure, finds the largest distance from a vertex of
  // either mesh to the other's surface (brute force over every face here),
  // never above the report's Hausdorff; and a report made with it is the
  // report made without it.
  void vertexHausdorffIsTheVerticesMaximum() {
    const MeshData orig = curvedGrid(24, 10.0, 0.4, true);
    DecimateOptions d;
    d.targetRatio = 0.1;
    const DecimateResult r = decimate(orig, d);
    QVERIFY2(r.ok(), r.error.c_str());
    const MeshData& s = r.mesh;
    const glm::dvec3 toOrig = s.origin - orig.origin;
    auto farthest = [](const MeshData& from, const MeshData& to, const glm::dvec3& offset) {
      double worst = 0;
      for (const glm::vec3& v : from.positions) {
        double best = HUGE_VAL;
        for (size_t f = 0; f < to.triangleCount(); ++f) {
          glm::dvec3 p, bary;
          const glm::dvec3 a(to.positions[to.indices[f * 3]]), b(to.positions[to.indices[f * 3 + 1]]),
              c(to.positions[to.indices[f * 3 + 2]]);
          best = std::min(best, closestPointOnTriangle(glm::dvec3(v) + offset, a, b, c, p, bary));
        }
        worst = std::max(worst, std::sqrt(best));
      }
      return worst;
    };
    const double bruteForward = farthest(orig, s, -toOrig), bruteBackward = farthest(s, orig, toOrig);
    const double brute = std::max(bruteForward, bruteBackward);
    const ErrorMeter meter(orig);
    const ErrorMeter::VertexCheck check = meter.checkVertices(s);
    const double atVertices = check.hausdorff();
    QVERIFY2(brute > 1e-3, qPrintable(QString::number(brute)));  // 10% of a curved grid is off it somewhere
    QVERIFY2(std::abs(atVertices - brute) <= 1e-12 * brute,
             qPrintable(QString("%1 vs %2").arg(atVertices, 0, 'g', 17).arg(brute, 0, 'g', 17)));
    QVERIFY(std::abs(check.forward - bruteForward) <= 1e-12 * brute);
    QVERIFY(std::abs(check.backward - bruteBackward) <= 1e-12 * brute);
    const ErrorReport e = meter.measure(s);
    QVERIFY(atVertices <= e.hausdorff);
    const ErrorReport withCheck = meter.measure(s, nullptr, &check);
    QCOMPARE(withCheck.hausdorff, e.hausdorff);
    QCOMPARE(withCheck.forward.max, e.forward.max);
    QCOMPARE(withCheck.backward.max, e.backward.max);
    QCOMPARE(withCheck.mean, e.mean);
    QCOMPARE(withCheck.p95, e.p95);
  }

  // The certified bracket: a far denser sampling than the report's (an
  // independent estimate from below) lands between the report's maximum
  // and the upper bound, at every ratio, also at UTM coordinates; and the
  // bound is of use, within 2% of the dense sampling's maximum (its slack
  // is 1%). At 50% here the report's 10 samples a face found 4.93 mm,
  // 3,000 a face 5.63 mm, the bound 5.68 mm.
  void hausdorffUpperBoundBracketsTheTruth_data() {
    QTest::addColumn<double>("ratio");
    QTest::addColumn<bool>("utm");
    QTest::newRow("50%") << 0.5 << false;
    QTest::newRow("10%") << 0.1 << false;
    QTest::newRow("2% at UTM") << 0.02 << true;
  }
  void hausdorffUpperBoundBracketsTheTruth() {
    QFETCH(double, ratio);
    QFETCH(bool, utm);
    MeshData orig = curvedGrid(20, 10.0, 0.5, true);
    if (utm) orig.origin = glm::dvec3(656059.0, 5514553.0, 1713.0);
    DecimateOptions d;
    d.targetRatio = ratio;
    const DecimateResult r = decimate(orig, d);
    QVERIFY2(r.ok(), r.error.c_str());
    const ErrorMeter meter(orig);
    const ErrorReport e = meter.measure(r.mesh);
    const HausdorffBound h = meter.hausdorffUpperBound(r.mesh, e.hausdorff);
    ErrorOptions dense;
    dense.samplesPerFace = 3000;
    dense.seed = 7;
    const double denser = measureError(orig, r.mesh, dense).hausdorff;
    const QString what = QString("sampled %1, 3000 a face %2, upper %3 (%4 pieces, %5 s)")
                             .arg(e.hausdorff, 0, 'g', 9).arg(denser, 0, 'g', 9).arg(h.upper, 0, 'g', 9)
                             .arg(h.pieces).arg(h.seconds);
    qInfo("%s", qPrintable(what));
    QCOMPARE(h.lower, e.hausdorff);
    QVERIFY2(denser <= h.upper, qPrintable(what));
    QVERIFY2(e.hausdorff <= denser && h.upper <= 1.02 * denser, qPrintable(what));
  }

  // ErrorOptions::certify: the report carries the certified upper bound
  // (a dense sampling never passes it), and a maximum error is then met
  // by the bound, so by every point: checked by 1,000 samples a face.
  // On this smooth grid the 10 samples a face see less than the true
  // maximum (docs/meshes.md, "How far off the sampled maximum can be"):
  // uncertified, this bound was "met" at 1.91 mm sampled by a result
  // whose maximum is 2.20 mm (logged, not asserted: that is the
  // sampling's miss, not a property to keep); certified, a third run
  // met it at 1.80 mm.
  void aCertifiedMaximumErrorHoldsEverywhere() {
    const MeshData orig = curvedGrid(40, 10.0, 0.8, false);
    ErrorOptions dense;
    dense.samplesPerFace = 1000;
    dense.seed = 5;
    for (bool certify : {false, true}) {
      ProcessOptions o;
      o.decimate = true;
      o.decimation.targetRatio = 0.0;
      o.decimation.maxError = 0.0021;
      o.error.certify = certify;
      const ProcessResult r = processMesh(orig, o);
      QVERIFY2(r.ok(), r.error.c_str());
      const ErrorReport& e = r.report.error;
      const double truth = measureError(orig, r.mesh, dense).hausdorff;
      qInfo("certify %d: sampled %.5g, certified %.5g, 1000 a face %.5g m; %zu triangles, %d runs", int(certify),
            e.hausdorff, e.hausdorffUpper, truth, r.mesh.triangleCount(), r.report.maxErrorPasses);
      QCOMPARE(e.certified, certify);
      QVERIFY(e.hausdorff <= 0.0021);
      if (!certify) continue;
      QVERIFY(e.hausdorff <= e.hausdorffUpper && e.certifiedPieces > 0 && e.certifySeconds > 0);
      QVERIFY(truth <= e.hausdorffUpper);
      QVERIFY(e.hausdorffUpper <= 0.0021);
      QVERIFY(truth <= 0.0021);
      // The report keeps it.
      const std::string text = hs::writeJson(toJson(r.report));
      std::string error;
      const std::optional<hs::Json> doc = hs::parseJson(text, error);
      QVERIFY2(doc, error.c_str());
      QCOMPARE((*doc)["error"]["hausdorff_certified"]["upper_m"].get<double>(), e.hausdorffUpper);
      hs::JsonReader reader(error);
      ProcessReport back;
      QVERIFY2(fromJson(reader, *doc, "", back), error.c_str());
      QVERIFY(back.error.certified);
      QCOMPARE(back.error.hausdorffUpper, e.hausdorffUpper);
      QCOMPARE(back.error.certifiedPieces, e.certifiedPieces);
    }
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
