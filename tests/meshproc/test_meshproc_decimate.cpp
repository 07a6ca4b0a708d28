// Decimation: round trip at 100%, targets, UTM-offset invariance, seams and
// boundaries on their polylines, borders of a quad-dominant scan that do
// not sag, no flips on a sphere, an unevenly sampled scan decimating like an
// even one, determinism across thread counts, region
// levels against one greedy queue, locked tile borders, Cancel.
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "mesh/mesh_import.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "mesh_builders.h"

using namespace hs::mesh;
using hs::test::curvedGrid;
using hs::test::icosphere;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

MeshData bunny() {
  ImportOptions o;
  o.up = UpAxis::Z;
  ImportResult r = importMesh(kBunny, o);
  if (!r.ok()) qFatal("cannot read the bunny: %s", r.error.c_str());
  return std::move(*r.mesh);
}

std::set<std::tuple<float, float, float>> pointSet(const std::vector<glm::vec3>& pts) {
  std::set<std::tuple<float, float, float>> s;
  for (const auto& p : pts) s.insert({p.x, p.y, p.z});
  return s;
}

}  // namespace

class TestMeshprocDecimate : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;

 private slots:
  void hundredPercentChangesNothing() {
    const MeshData in = bunny();
    DecimateOptions o;
    o.targetRatio = 1.0;
    const DecimateResult r = decimate(in, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh.triangleCount(), in.triangleCount());
    QVERIFY(r.mesh.positions == in.positions);
    QVERIFY(r.mesh.indices == in.indices);
    QVERIFY(r.mesh.normals == in.normals);
    QCOMPARE(r.report.collapses, size_t(0));
    QVERIFY(r.report.targetReached);
    // And the error metric agrees: nothing moved.
    const ErrorReport e = measureError(in, r.mesh);
    QCOMPARE(e.hausdorff, 0.0);
  }

  void ratioCountAndErrorTargets() {
    const MeshData in = bunny();
    DecimateOptions ratio;
    ratio.targetRatio = 0.25;
    const DecimateResult a = decimate(in, ratio);
    QVERIFY2(a.ok(), a.error.c_str());
    const size_t want = size_t(std::llround(0.25 * double(in.triangleCount())));
    QVERIFY(a.mesh.triangleCount() <= want && a.mesh.triangleCount() + 2 >= want);
    QVERIFY(a.report.targetReached);

    DecimateOptions count;
    count.targetTriangles = 5000;
    const DecimateResult b = decimate(in, count);
    QVERIFY(b.mesh.triangleCount() <= 5000 && b.mesh.triangleCount() >= 4998);

    // Maximum error alone: every collapse stays within it (estimate), and
    // the measured Hausdorff is of the same order.
    DecimateOptions err;
    err.targetRatio = 0.0;
    err.maxError = 0.0002;  // 0.2 mm on a 0.2 m scan
    const DecimateResult c = decimate(in, err);
    QVERIFY2(c.ok(), c.error.c_str());
    QVERIFY(c.mesh.triangleCount() < in.triangleCount() / 2);
    QVERIFY(c.report.maxEstimatedError <= 0.0002);
    const ErrorReport e = measureError(in, c.mesh);
    QVERIFY2(e.hausdorff < 4 * 0.0002, qPrintable(QString::number(e.hausdorff)));
  }

  void parseTargets() {
    DecimateOptions o;
    std::string err;
    QVERIFY(parseDecimateTarget("500k", o, err));
    QCOMPARE(o.targetTriangles, size_t(500000));
    QVERIFY(parseDecimateTarget("2.5M", o, err));
    QCOMPARE(o.targetTriangles, size_t(2500000));
    QVERIFY(parseDecimateTarget("10%", o, err));
    QCOMPARE(o.targetTriangles, size_t(0));
    QCOMPARE(o.targetRatio, 0.1);
    QVERIFY(!parseDecimateTarget("lots", o, err));
    QVERIFY2(err.find("lots") != std::string::npos, err.c_str());
    QVERIFY(!parseDecimateTarget("150%", o, err));
  }

  // The same scan at the origin and at UTM coordinates: the decimator works
  // relative to the mesh's own centre, so the shapes agree.
  void utmOffsetGivesTheSameShape() {
    const glm::dvec3 offset(656059.0, 5514553.0, 1713.0);
    MeshData a = bunny();
    // Coordinates on a 2^-20 m grid: exact in decimal and in double at
    // both places, so the file itself carries no rounding difference.
    for (auto& p : a.positions) p = glm::round(p * 1048576.0f) / 1048576.0f;
    a.origin = glm::dvec3(0.0);
    const std::string pa = tmp_.filePath("near.obj").toStdString(), pb = tmp_.filePath("utm.obj").toStdString();
    hs::test::writeObj(pa, a, glm::dvec3(0.0), 20, false);
    hs::test::writeObj(pb, a, offset, 20, false);
    ImportOptions io;
    io.up = UpAxis::Z;
    const ImportResult ra = importMesh(pa, io), rb = importMesh(pb, io);
    QVERIFY2(ra.ok() && rb.ok(), (ra.error + rb.error).c_str());
    QVERIFY(std::abs(rb.mesh->origin.y - offset.y) < 1.0);  // really at UTM northing

    DecimateOptions o;
    o.targetRatio = 0.1;
    const DecimateResult da = decimate(*ra.mesh, o), db = decimate(*rb.mesh, o);
    QVERIFY(da.ok() && db.ok());
    QCOMPARE(da.mesh.triangleCount(), db.mesh.triangleCount());
    const double diag = measureError(*ra.mesh, da.mesh).bboxDiagonal;
    double worst = 0;
    for (size_t v = 0; v < da.mesh.vertexCount(); ++v) {
      const glm::dvec3 wa = da.mesh.origin + glm::dvec3(da.mesh.positions[v]);
      const glm::dvec3 wb = db.mesh.origin + glm::dvec3(db.mesh.positions[v]) - offset;
      worst = std::max(worst, glm::length(wa - wb));
    }
    QVERIFY2(worst <= 1e-6 * diag, qPrintable(QString("vertex difference %1 m of %2 m").arg(worst).arg(diag)));
    // Shape against shape (independent of vertex order).
    MeshData shifted = db.mesh;
    shifted.origin -= offset;
    const ErrorReport e = measureError(da.mesh, shifted);
    QVERIFY2(e.hausdorff <= 1e-6 * diag, qPrintable(QString::number(e.hausdorff)));
  }

  // Boundary and UV-seam vertices only merge along their polyline and never
  // move: every boundary/seam vertex left is an original one, and the
  // texture lands where it did.
  // The stiff case for the float vertex records (positions relative to the
  // mesh's centre, quadrics relative to their vertex): millimetre triangles
  // near the local origin of a mesh that reaches 1 km away, so that they
  // lie 500 m from the centre, where a float resolves 61 um (6% of a
  // triangle's edge). Decimated with the far part, the patch keeps about
  // the error it gets decimated alone (where the centre is beside it).
  void millimetreDetailFarFromTheCentre() {
    const MeshData patch = curvedGrid(40, 0.04, 0.004, false);  // 1 mm cells, 4 mm relief
    MeshData far = curvedGrid(2, 10.0, 0.0, false);
    MeshData both = patch;
    const uint32_t base = uint32_t(both.positions.size());
    for (const auto& p : far.positions) both.positions.push_back(p + glm::vec3(1000.0f, 0.0f, 0.0f));
    for (uint32_t i : far.indices) both.indices.push_back(base + i);
    both.uvs.clear(), both.normals.clear(), both.submeshes.clear();
    MeshData alone = patch;
    alone.uvs.clear(), alone.normals.clear();

    DecimateOptions o;
    o.targetTriangles = patch.triangleCount() / 4;
    const DecimateResult ra = decimate(alone, o);
    o.targetTriangles += far.triangleCount();  // the far quads are flat and large: they go last
    const DecimateResult rb = decimate(both, o);
    QVERIFY(ra.ok() && rb.ok());
    // The patch's part of the joint result.
    MeshData part;
    std::vector<uint32_t> newIndex(rb.mesh.vertexCount(), UINT32_MAX);
    for (size_t f = 0; f < rb.mesh.triangleCount(); ++f) {
      const uint32_t* t = &rb.mesh.indices[f * 3];
      if (rb.mesh.positions[t[0]].x >= 1.0f || rb.mesh.positions[t[1]].x >= 1.0f || rb.mesh.positions[t[2]].x >= 1.0f)
        continue;
      for (int k = 0; k < 3; ++k) {
        if (newIndex[t[k]] == UINT32_MAX) {
          newIndex[t[k]] = uint32_t(part.positions.size());
          part.positions.push_back(rb.mesh.positions[t[k]]);
        }
        part.indices.push_back(newIndex[t[k]]);
      }
    }
    // (A boundary collapse removes one face, so the counts may land one apart.)
    QVERIFY(part.triangleCount() + 1 >= ra.mesh.triangleCount() && part.triangleCount() <= ra.mesh.triangleCount() + 1);
    const ErrorReport ea = measureError(alone, ra.mesh), eb = measureError(alone, part);
    qInfo("patch alone: Hausdorff %.3g m, mean %.3g m; 500 m from the centre: %.3g m, mean %.3g m", ea.hausdorff, ea.mean,
          eb.hausdorff, eb.mean);
    QVERIFY(ea.hausdorff > 0.0);
    // The far part changes the order of collapses a little: the double
    // records before them measured 3.19e-5 m here (1.41x), these 2.92e-5 m
    // and a mean within 4%. Float rounding of the placements (a 61 um grid
    // against a 23 um error) would show in both.
    QVERIFY2(eb.hausdorff <= 1.5 * ea.hausdorff, qPrintable(QString::number(eb.hausdorff)));
    QVERIFY2(eb.mean <= 1.2 * ea.mean, qPrintable(QString::number(eb.mean)));
    QCOMPARE(eb.flippedNormals, size_t(0));
  }

  void seamsAndBoundariesStayOnTheirPolylines() {
    const MeshData in = curvedGrid(60, 10.0, 0.4, true);
    // The seam really is one: vertices on it exist twice with different UVs.
    QVERIFY(in.vertexCount() > 61 * 61);
    DecimateOptions o;
    o.targetRatio = 0.05;
    const DecimateResult r = decimate(in, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.seamVertices > 0 && r.report.boundaryVertices > 0);
    ErrorOptions eo;
    eo.textureWidth = eo.textureHeight = 1024;
    const ErrorReport e = measureError(in, r.mesh, eo);
    QVERIFY(e.constrainedVerticesOut > 8);
    QCOMPARE(e.constrainedVerticesMoved, size_t(0));
    QVERIFY(e.uvMeasured);
    QVERIFY2(e.uvP95Texels < 1.0, qPrintable(QString::number(e.uvP95Texels)));
    // Every output vertex sitting at a seam/boundary position is one of the
    // input's vertices there, exactly.
    const auto original = pointSet(in.positions);
    for (const auto& p : r.mesh.positions) {
      const bool onBorder = p.x == 0.0f || p.y == 0.0f || p.x == 10.0f || p.y == 10.0f;
      if (onBorder) QVERIFY(original.count({p.x, p.y, p.z}));
    }
    // Seam vertices keep both their UVs: some output positions still carry two.
    std::map<std::tuple<float, float, float>, int> uvCount;
    for (const auto& p : r.mesh.positions) ++uvCount[{p.x, p.y, p.z}];
    QVERIFY(std::any_of(uvCount.begin(), uvCount.end(), [](const auto& kv) { return kv.second == 2; }));
  }

  // Issue 11 item 5: on a quad-dominant scan the largest error sat on the
  // open border, where a border vertex merging into its neighbour was
  // costed by its planes and not by how far the border line then sags.
  // The bound comes from the exact surface, not from the decimator: the
  // sag of the border's chords when every other border vertex goes (what
  // the decimator did there before), against the result's Hausdorff
  // distance measured by the error report and against each input border
  // vertex's distance from the result's border polyline, measured here.
  void quadScanBordersDoNotSagAtHalf() {
    const int n = 60;
    const double size = 10.0, amplitude = 0.6, noise = 0.001;  // 1 mm of noise on 17 cm quads
    const MeshData in = hs::test::quadScanPatch(n, size, amplitude, noise);
    const double h = size / n;
    double sag = 0.0;  // of the noise-free relief, along all four borders
    for (int k = 1; k < n; ++k) {
      const double s = h * k;
      auto chordSag = [&](double x0, double y0, double x1, double y1, double x2, double y2) {
        const double z0 = hs::test::quadScanRelief(x0, y0, size, amplitude), z2 = hs::test::quadScanRelief(x2, y2, size, amplitude);
        return std::abs(hs::test::quadScanRelief(x1, y1, size, amplitude) - 0.5 * (z0 + z2));
      };
      sag = std::max({sag, chordSag(s - h, 0, s, 0, s + h, 0), chordSag(s - h, size, s, size, s + h, size),
                      chordSag(0, s - h, 0, s, 0, s + h), chordSag(size, s - h, size, s, size, s + h)});
    }
    DecimateOptions o;
    o.targetRatio = 0.5;
    const DecimateResult r = decimate(in, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.report.boundaryVertices > 0);
    const ErrorReport e = measureError(in, r.mesh);
    // The result's border polyline: its edges with one face.
    std::map<std::pair<uint32_t, uint32_t>, int> edgeFaces;
    for (size_t i = 0; i < r.mesh.indices.size(); i += 3)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = r.mesh.indices[i + size_t(k)], b = r.mesh.indices[i + size_t((k + 1) % 3)];
        ++edgeFaces[std::minmax(a, b)];
      }
    double borderWorst = 0.0;
    for (const auto& p : in.positions) {
      if (p.x != 0.0f && p.y != 0.0f && p.x != float(size) && p.y != float(size)) continue;
      double best = HUGE_VAL;
      for (const auto& [edge, faces] : edgeFaces) {
        if (faces != 1) continue;
        const glm::dvec3 a(r.mesh.positions[edge.first]), ab = glm::dvec3(r.mesh.positions[edge.second]) - a;
        const double t = std::clamp(glm::dot(glm::dvec3(p) - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        best = std::min(best, glm::length(glm::dvec3(p) - (a + t * ab)));
      }
      borderWorst = std::max(borderWorst, best);
    }
    qInfo("sag of every other border vertex gone %.3g m; Hausdorff %.3g m; worst border vertex %.3g m", sag,
          e.hausdorff, borderWorst);
    // Measured (sag 6.7 mm): before the fix Hausdorff 4.8 mm and a border
    // vertex 5.2 mm off the result's border; with the chord term alone
    // 2.9 and 2.9 mm (the length tie-break of 1e-4 still outweighed the
    // errors); with the smaller tie-break and placement pull 2.2 and 1.2.
    QVERIFY2(borderWorst < 0.25 * sag, qPrintable(QString::number(borderWorst)));
    QVERIFY2(e.hausdorff < 0.5 * sag, qPrintable(QString::number(e.hausdorff)));
  }

  void noFlippedNormalsOnASphereAtOnePercent() {
    const MeshData in = icosphere(6, 1.0);  // 81920 faces
    DecimateOptions o;
    o.targetRatio = 0.01;
    const DecimateResult r = decimate(in, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(r.mesh.triangleCount() <= 820);
    for (size_t f = 0; f < r.mesh.triangleCount(); ++f) {
      const glm::dvec3 a(r.mesh.positions[r.mesh.indices[f * 3]]), b(r.mesh.positions[r.mesh.indices[f * 3 + 1]]),
          c(r.mesh.positions[r.mesh.indices[f * 3 + 2]]);
      QVERIFY2(glm::dot(glm::cross(b - a, c - a), a + b + c) > 0, qPrintable(QString("face %1 faces inwards").arg(f)));
    }
    const ErrorReport e = measureError(in, r.mesh);
    QCOMPARE(e.flippedNormals, size_t(0));
    QVERIFY(e.hausdorff < 0.05);  // an 820-face sphere of radius 1
  }

  // A scan sampled unevenly (a remesher's or a photogrammetry mesher's
  // grading: long thin triangles, quality well under the sliver bound, on
  // one side) decimates about as well as the same surface sampled evenly,
  // and flips nothing. The sliver rule once compared each face with its own
  // old shape and refused every collapse that thinned a face of the
  // slivered side (10,000 refusals): the graded sphere's mean error was
  // 1.8x the even one's at 10% and 4.2x at 3% (Hausdorff 4.1x); now 1.0x.
  void unevenlySampledScanDecimatesLikeAnEvenOne() {
    const MeshData graded = hs::test::gradedBumpySphere(240, 120, 0.85);  // 57,120 faces
    MeshData even = icosphere(6, 10.0);                                    // 81,920 faces
    for (glm::vec3& p : even.positions) {
      const glm::dvec3 n = glm::normalize(glm::dvec3(p));
      p = glm::vec3(hs::test::bumpyRadius(n) * n);
    }
    computeVertexNormals(even);
    for (double ratio : {0.1, 0.03}) {
      const QString where = QString("at %1% of the graded sphere").arg(ratio * 100);
      DecimateOptions o;
      o.targetTriangles = size_t(ratio * double(graded.triangleCount()));
      const DecimateResult rg = decimate(graded, o), re = decimate(even, o);
      QVERIFY2(rg.ok() && re.ok(), (rg.error + re.error).c_str());
      QVERIFY(rg.report.targetReached && re.report.targetReached);
      const ErrorReport eg = measureError(graded, rg.mesh), ee = measureError(even, re.mesh);
      const QString numbers = where + QString(": graded Hausdorff %1 mean %2, even %3 %4")
                                          .arg(eg.hausdorff).arg(eg.mean).arg(ee.hausdorff).arg(ee.mean);
      QVERIFY2(eg.mean <= 1.25 * ee.mean, qPrintable(numbers));
      // The maximum also carries the graded grid's own chords (5 mm on its
      // sparse side), so it gets more room than the mean.
      QVERIFY2(eg.hausdorff <= 2.0 * ee.hausdorff, qPrintable(numbers));
      QCOMPARE(eg.flippedNormals, size_t(0));
      QCOMPARE(ee.flippedNormals, size_t(0));
    }
  }

  // Output depends on the input only, not on the number of threads, also
  // when the mesh is cut into many regions.
  void deterministicForAnyThreadCount() {
    const MeshData in = bunny();
    for (size_t perRegion : {size_t(1000000), size_t(8000)}) {
      uint64_t first = 0;
      for (unsigned threads : {1u, 2u, 3u}) {
        DecimateOptions o;
        o.targetRatio = 0.1;
        o.threads = threads;
        o.facesPerRegion = perRegion;
        const DecimateResult r = decimate(in, o);
        QVERIFY(r.ok());
        if (perRegion == 8000) QVERIFY(r.report.regions > 4);
        const uint64_t h = contentHash(r.mesh);
        if (threads == 1) first = h;
        QCOMPARE(h, first);
      }
    }
  }

  // Many regions (level 0's rounds, then merging pairwise and catching
  // the strips up) against one region (one greedy queue over the whole
  // mesh, the order the levels approximate): about the same error, and
  // the parallel levels, not the serial last region, make most of the
  // collapses.
  void regionLevelsFollowOneGreedyOrder() {
    const MeshData in = bunny();
    for (double ratio : {0.1, 0.02}) {
      DecimateOptions one, many;
      one.targetRatio = many.targetRatio = ratio;
      one.facesPerRegion = 10000000;
      many.facesPerRegion = 5000;
      const DecimateResult a = decimate(in, one), b = decimate(in, many);
      QVERIFY(a.ok() && b.ok());
      QCOMPARE(a.report.regions, 1u);
      QVERIFY(b.report.regions >= 12);
      QVERIFY(b.report.levels >= 3);
      // On the target, or one below it (a collapse removes two faces).
      for (const DecimateResult* r : {&a, &b})
        QVERIFY(r->mesh.triangleCount() <= r->report.targetTriangles &&
                r->mesh.triangleCount() + 1 >= r->report.targetTriangles);
      const ErrorReport ea = measureError(in, a.mesh), eb = measureError(in, b.mesh);
      qInfo("ratio %.2f: one region Hausdorff %.3e mean %.3e; %u regions %.3e / %.3e, last region %zu of %zu collapses",
            ratio, ea.hausdorff, ea.mean, b.report.regions, eb.hausdorff, eb.mean, b.report.lastRegionCollapses,
            b.report.collapses);
      QVERIFY(eb.mean < 1.05 * ea.mean);
      QVERIFY(eb.hausdorff < 1.5 * ea.hausdorff);
      // Where the regions' floors (3,000 faces each) do not bind: at 10%
      // of the bunny 14 regions' floors are 6x the target, and what they
      // held back is the last region's (docs/meshes.md, "Two cores").
      if (ratio == 0.5) QVERIFY(b.report.lastRegionCollapses * 5 < b.report.collapses);
      QCOMPARE(a.report.lastRegionCollapses, a.report.collapses);  // one region: all of it is the last
    }
  }

  // Tile borders: with lockBoundaries every boundary vertex stays.
  void lockedBoundariesStay() {
    const MeshData in = curvedGrid(40, 10.0, 0.5, false);
    DecimateOptions o;
    o.targetRatio = 0.05;
    o.lockBoundaries = true;
    const DecimateResult r = decimate(in, o);
    QVERIFY(r.ok());
    size_t border = 0;
    const auto out = pointSet(r.mesh.positions);
    for (const auto& p : in.positions)
      if (p.x == 0.0f || p.y == 0.0f || p.x == 10.0f || p.y == 10.0f) {
        ++border;
        QVERIFY(out.count({p.x, p.y, p.z}));
      }
    QCOMPARE(border, size_t(160));
    QCOMPARE(r.report.fixedVertices, size_t(160));
  }

  // Scans come with defects: fins (three faces on an edge), faces that
  // touch the surface at one vertex (bow-ties), faces stored twice, either
  // way round. Random ones of each kind on a grid with a UV seam, several
  // regions: each decimates (the defects are split, never refused) to a
  // valid mesh near its target, the same for any thread count, with no
  // boundary or seam vertex off the input's (the error report's check:
  // a hole opened in the surface puts one there). When the split paired
  // a face with its reversed copy, the face left the surface with it and
  // 10 of these 40 meshes came out of 2% with a hole where it had been.
  void meshesWithRandomDefectsDecimate() {
    const MeshData grid = curvedGrid(40, 10.0, 0.4, true);  // 3,200 faces
    std::mt19937 rng(11);
    for (int trial = 0; trial < 40; ++trial) {
      MeshData in = grid;
      const int defects = 1 + trial % 13;
      for (int d = 0; d < defects; ++d) hs::test::addDefect(in, grid, (trial + d) % 5, rng);
      for (double ratio : {0.1, 0.02}) {
        const QString where = QString("trial %1, ratio %2").arg(trial).arg(ratio);
        uint64_t first = 0;
        for (unsigned threads : {1u, 2u}) {
          DecimateOptions o;
          o.targetRatio = ratio;
          o.threads = threads;
          o.facesPerRegion = 1000;  // 3 regions
          const DecimateResult r = decimate(in, o);
          QVERIFY2(r.ok(), qPrintable(where + ": " + QString::fromStdString(r.error)));
          const MeshData& out = r.mesh;
          QVERIFY2(out.triangleCount() <= size_t(std::ceil(ratio * in.triangleCount() * 1.05)),
                   qPrintable(where + QString(": %1 triangles").arg(out.triangleCount())));
          for (size_t t = 0; t < out.triangleCount(); ++t) {
            const uint32_t i = out.indices[t * 3], j = out.indices[t * 3 + 1], l = out.indices[t * 3 + 2];
            QVERIFY2(i < out.vertexCount() && j < out.vertexCount() && l < out.vertexCount(), qPrintable(where));
            QVERIFY2(i != j && j != l && i != l, qPrintable(where));
          }
          const uint64_t h = contentHash(out);
          if (threads == 1) {
            first = h;
            const ErrorReport e = measureError(in, out, {});
            QCOMPARE(e.constrainedVerticesMoved, size_t(0));
            QVERIFY2(std::isfinite(e.hausdorff) && e.rel(e.hausdorff) < 0.02,
                     qPrintable(where + QString(": Hausdorff %1 of diagonal %2").arg(e.hausdorff).arg(e.bboxDiagonal)));
          }
          QVERIFY2(h == first, qPrintable(where + ": differs between 1 and 2 threads"));
        }
      }
    }
  }

  void badInputIsRefusedWithAMessage() {
    MeshData m = curvedGrid(4, 1.0, 0.0, false);
    m.indices[5] = 999;
    DecimateResult r = decimate(m, {});
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("999") != std::string::npos && r.error.find("clean") != std::string::npos, r.error.c_str());
    m = curvedGrid(4, 1.0, 0.0, false);
    m.positions[3].x = NAN;
    r = decimate(m, {});
    QVERIFY2(!r.ok() && r.error.find("NaN") != std::string::npos, r.error.c_str());
    MeshData empty;
    empty.positions = {{0, 0, 0}};
    r = decimate(empty, {});
    QVERIFY2(!r.ok() && r.error.find("no faces") != std::string::npos, r.error.c_str());
    // All faces degenerate (every corner of each face at one point).
    MeshData flat;
    flat.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    flat.indices = {0, 1, 2, 3, 4, 5};
    DecimateOptions half;
    half.targetRatio = 0.5;
    r = decimate(flat, half);
    QVERIFY2(!r.ok() && r.error.find("degenerate") != std::string::npos, r.error.c_str());
  }

  void cancelStopsIt() {
    const MeshData in = bunny();
    hs::Progress progress;
    progress.cancel();
    const DecimateResult r = decimate(in, {}, &progress);
    QVERIFY(r.cancelled);
    QVERIFY(!r.ok());
  }

  void progressIsReported() {
    const MeshData in = bunny();
    std::vector<double> seen;
    hs::Progress progress([&](double f, std::string_view) { seen.push_back(f); });
    DecimateOptions o;
    o.targetRatio = 0.05;
    o.threads = 2;
    const DecimateResult r = decimate(in, o, &progress);
    QVERIFY(r.ok());
    QVERIFY(seen.size() >= 3);
    QCOMPARE(seen.back(), 1.0);
    QVERIFY(std::is_sorted(seen.begin(), seen.end()));
  }
};

QTEST_GUILESS_MAIN(TestMeshprocDecimate)
#include "test_meshproc_decimate.moc"
