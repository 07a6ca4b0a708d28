// The minimax vertex refinement (meshproc/max_error_refine.h): an exact
// case whose optimum is known, the error report before and after on noisy
// scans, what may not move, determinism, far-from-origin coordinates.
#include <QtTest>

#include <map>
#include <random>
#include <set>

#include "defect_cases.h"
#include "mesh_builders.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/max_error_refine.h"
#include "meshproc/mesh_process.h"
#include "meshproc/minimax_move.h"

using namespace hs::mesh;

namespace {

// A tent: a 3 x 3 grid of unit cells... the 2 x 2 quads around a centre
// raised by h, each quad cut from the centre, so the surface is four
// planes through the apex. `result`: its corners and the centre at
// height `centre` (four triangles), which lies on the tent's planes
// exactly when centre == h.
MeshData tent(double h, glm::dvec3 origin = glm::dvec3(0.0), double size = 1.0) {
  MeshData m;
  m.origin = origin;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i)
      m.positions.emplace_back(float(i * size), float(j * size), i == 0 && j == 0 ? float(h) : 0.0f);
  auto id = [](int i, int j) { return uint32_t((j + 1) * 3 + (i + 1)); };
  const int ring[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}};
  for (int k = 0; k < 8; ++k)
    m.indices.insert(m.indices.end(), {id(0, 0), id(ring[k][0], ring[k][1]), id(ring[(k + 1) % 8][0], ring[(k + 1) % 8][1])});
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  computeVertexNormals(m);
  return m;
}

MeshData coarseTent(double centre, glm::dvec3 origin = glm::dvec3(0.0), double size = 1.0) {
  MeshData m;
  m.origin = origin;
  const float a = float(size);
  m.positions = {{0, 0, float(centre)}, {-a, -a, 0}, {a, -a, 0}, {a, a, 0}, {-a, a, 0}};
  m.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  computeVertexNormals(m);
  return m;
}

// Edges with other than two faces, by vertex index (boundaries, seams,
// non-manifold edges): their vertices may not move.
std::set<uint32_t> constrainedVertices(const MeshData& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> faces;
  for (size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++faces[std::minmax(m.indices[i + size_t(k)], m.indices[i + size_t((k + 1) % 3)])];
  std::set<uint32_t> out;
  for (const auto& [e, n] : faces)
    if (n != 2) out.insert(e.first), out.insert(e.second);
  return out;
}

}  // namespace

class TestMeshprocRefine : public QObject {
  Q_OBJECT

 private slots:
  // The one-dimensional move against brute force (a grid of 200,001 moves
  // over the reach), on random samples at scales from a micrometre to ten
  // kilometres and with weights down to 1e-6 (stiff: one sample barely
  // moves with the vertex): the minimax move's largest distance is the
  // grid's least, and the move towards the least-squares one stays within
  // the slack and is the nearest such move to it.
  void movesAgainstBruteForce() {
    using namespace hs::mesh::minimax;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double scale : {1e-6, 1.0, 1e4})
      for (int trial = 0; trial < 40; ++trial) {
        std::vector<Constraint> cs(size_t(2 + trial % 30));
        for (Constraint& c : cs) {
          const double across = 0.1 * scale * u(rng);
          c = {across * across, scale * (2.0 * u(rng) - 1.0), trial % 4 == 0 ? 1e-6 + u(rng) * 1e-6 : u(rng)};
        }
        const double reach = 2.0 * scale;
        const double m = minimaxMove(cs, reach);
        const int steps = 200000;
        double gridLeast = HUGE_VAL;
        for (int i = 0; i <= steps; ++i) gridLeast = std::min(gridLeast, worst(cs, -reach + 2.0 * reach * i / steps));
        const QString what = QString("scale %1 trial %2").arg(scale).arg(trial);
        QVERIFY2(worst(cs, m) <= gridLeast * (1.0 + 1e-6), qPrintable(what));
        for (double slack : {0.02, 0.2}) {
          const double t = towardsLeastSquares(cs, m, reach, slack);
          double sw = 0, swa = 0;
          for (const Constraint& c : cs) sw += c.weight * c.weight, swa += c.weight * c.along;
          const double ls = std::clamp(swa / sw, -reach, reach);
          const double allowed = (1.0 + slack) * (1.0 + slack) * worst(cs, m);
          QVERIFY2(worst(cs, t) <= allowed * (1.0 + 1e-12), qPrintable(what));
          const double step = 2.0 * reach / steps;
          for (int i = 0; i <= steps; ++i) {
            const double d = -reach + step * i;
            if (worst(cs, d) <= allowed) QVERIFY2(std::abs(d - ls) >= std::abs(t - ls) - step, qPrintable(what));
          }
        }
      }
  }

  // The coarse tent's best centre is the apex (error 0). The first round
  // asks for the whole rise h and moves `damping` of it; each round then
  // takes `damping` of what is left.
  void aFlattenedApexRisesToTheApex() {
    const double h = 0.1;
    const MeshData original = tent(h);
    const ErrorMeter meter(original);
    for (int rounds : {1, 3}) {
      MeshData result = coarseTent(0.0);
      const double before = meter.measure(result).hausdorff;
      QVERIFY(std::abs(before - h) < 1e-6);  // the apex, h above the flat result
      RefineOptions o;
      o.iterations = rounds;
      const RefineReport r = refineMaxError(meter, result, o);
      QCOMPARE(r.candidates, size_t(1));  // the centre: the corners are on the border
      QCOMPARE(r.moved, size_t(1));
      const double left = std::pow(1.0 - o.damping, rounds);
      // (The samples' offsets across the normal are taken as fixed, an
      // upper bound, so each round stops a little short: 0.099 h, not h.)
      QVERIFY2(std::abs(double(result.positions[0].z) - h * (1.0 - left)) < 0.02 * h,
               qPrintable(QString("centre %1 after %2 rounds").arg(double(result.positions[0].z)).arg(rounds)));
      for (size_t v = 1; v < 5; ++v) QCOMPARE(result.positions[v], coarseTent(0.0).positions[v]);
      const double after = meter.measure(result).hausdorff;
      QVERIFY(std::abs(after - h * left) < 0.05 * h);  // the rest of the rise, as the error report measures it
      QVERIFY(std::abs(r.largestBefore - before) < 1e-6 && std::abs(r.largestAfter - after) < 0.05 * h);
    }
  }

  // Results it cannot improve come back as they were, nothing in them
  // turned into NaN: no faces at all; a centre collapsed onto a corner
  // (zero-area faces, a position two vertices share).
  void degenerateResultsAreLeftAlone() {
    const MeshData original = tent(0.1);
    const ErrorMeter meter(original);
    MeshData empty;
    const RefineReport none = refineMaxError(meter, empty);
    QCOMPARE(none.candidates, size_t(0));
    QCOMPARE(none.moved, size_t(0));
    MeshData collapsed = coarseTent(0.0);
    collapsed.positions[0] = collapsed.positions[1];
    const MeshData before = collapsed;
    const RefineReport r = refineMaxError(meter, collapsed);
    QCOMPARE(r.moved, size_t(0));
    QCOMPARE(collapsed.positions, before.positions);
    QVERIFY(std::isfinite(r.largestBefore) && std::isfinite(r.largestAfter));
  }

  // The same tent from 2 mm to 20 km across: the moves scale with it
  // (nothing in the solver is an absolute length).
  void theApexAtEveryScale() {
    for (double size : {1e-3, 1.0, 1e4}) {
      const double h = 0.1 * size;
      const MeshData original = tent(h, glm::dvec3(0.0), size);
      const ErrorMeter meter(original);
      MeshData result = coarseTent(0.0, glm::dvec3(0.0), size);
      RefineOptions o;
      o.iterations = 1;
      const RefineReport r = refineMaxError(meter, result, o);
      QCOMPARE(r.moved, size_t(1));
      const double rise = double(result.positions[0].z) / h;
      QVERIFY2(std::abs(rise - 0.7) < 0.02, qPrintable(QString("size %1: rose %2 h").arg(size).arg(rise)));
    }
  }

  // Already exact: nothing to gain, nothing moves.
  void anExactResultStaysPut() {
    const double h = 0.1;
    const MeshData original = tent(h);
    const ErrorMeter meter(original);
    MeshData result = coarseTent(h);
    const MeshData before = result;
    const RefineReport r = refineMaxError(meter, result);
    QCOMPARE(r.moved, size_t(0));
    QCOMPARE(result.positions, before.positions);
  }

  // The same tent 6,500 km from the origin (UTM-sized offsets): the moves
  // are computed relative to the meshes' own origins, so they are the
  // same to float precision.
  void farFromTheOriginTheSameMoves() {
    const glm::dvec3 utm(656059.25, 5514553.5, 1713.0);
    const MeshData nearTent = tent(0.1), farTent = tent(0.1, utm);
    const ErrorMeter near(nearTent), far(farTent);
    MeshData a = coarseTent(0.0), b = coarseTent(0.0, utm);
    refineMaxError(near, a);
    refineMaxError(far, b);
    QVERIFY(std::abs(double(a.positions[0].z) - double(b.positions[0].z)) < 1e-6);
    // And a result whose origin differs from the original's.
    MeshData c = coarseTent(0.0, glm::dvec3(0.0, 0.0, 5.0));
    for (auto& p : c.positions) p.z -= 5.0f;
    refineMaxError(near, c);
    QVERIFY(std::abs(double(c.positions[0].z) + 5.0 - double(a.positions[0].z)) < 1e-5);
  }

  // A noisy quad scan and a curved grid with a UV seam, decimated to 50%
  // and 10%: on the scan the error report's Hausdorff falls and its mean
  // hardly moves; on the smooth grid, whose largest distances lie on its
  // border and seam polylines (which stay), nothing gets worse. Boundary
  // and seam vertices stay where they were, so do the topology and the
  // UVs, and no face turns over.
  void lowersTheHausdorffOfDecimatedScans() {
    struct Case {
      const char* name;
      MeshData in;
      bool noisy;
    };
    const Case cases[] = {{"quad scan", hs::test::quadScanPatch(60, 10.0, 0.6, 0.001), true},
                          {"curved grid with a seam", hs::test::curvedGrid(80, 10.0, 1.0, true), false}};
    for (const Case& c : cases)
      for (double ratio : {0.5, 0.1}) {
        DecimateOptions d;
        d.targetRatio = ratio;
        const DecimateResult dr = decimate(c.in, d);
        QVERIFY(dr.ok());
        const ErrorMeter meter(c.in);
        const ErrorReport before = meter.measure(dr.mesh);
        MeshData refined = dr.mesh;
        const RefineReport r = refineMaxError(meter, refined);
        const ErrorReport after = meter.measure(refined);
        qInfo("%s at %g%%: Hausdorff %.4g -> %.4g m, mean %.4g -> %.4g m, %zu of %zu candidates moved, %.3f s", c.name,
              ratio * 100, before.hausdorff, after.hausdorff, before.mean, after.mean, r.moved, r.candidates, r.seconds);
        if (c.noisy) {
          QVERIFY(r.moved > 0);
          QVERIFY2(after.hausdorff < 0.95 * before.hausdorff, c.name);
          QVERIFY(r.largestAfter < r.largestBefore);  // the refinement's own estimate agrees
        } else {
          QVERIFY2(after.hausdorff <= before.hausdorff, c.name);
        }
        QVERIFY2(after.mean < 1.05 * before.mean, c.name);
        QCOMPARE(after.constrainedVerticesMoved, size_t(0));
        QVERIFY(after.flippedNormals <= before.flippedNormals);
        QCOMPARE(refined.indices, dr.mesh.indices);
        QCOMPARE(refined.uvs, dr.mesh.uvs);
        // Only interior vertices with a position of their own moved.
        std::multiset<std::tuple<float, float, float>> at;
        for (const auto& p : dr.mesh.positions) at.insert({p.x, p.y, p.z});
        const std::set<uint32_t> fixed = constrainedVertices(dr.mesh);
        for (uint32_t v = 0; v < refined.positions.size(); ++v) {
          if (refined.positions[v] == dr.mesh.positions[v]) continue;
          const auto& p = dr.mesh.positions[v];
          QVERIFY(!fixed.count(v));
          QCOMPARE(at.count({p.x, p.y, p.z}), size_t(1));
        }
      }
  }

  // The guard against turning a face over (RefineOptions::
  // keepFacingOriginal): on defect-campaign meshes where a move without it
  // leaves a face facing against the original surface near its centre
  // (the error report's flip count), with it the refined result has no
  // more flipped faces than the decimation alone. The cases were found by
  // running the campaign's meshes with the guard off; at least one must
  // still show what it prevents, or the test no longer tests the guard
  // (then look for another case the same way).
  void noMoveTurnsAFaceAgainstTheOriginal() {
    const std::vector<std::pair<unsigned, int>> found = {{1, 43}, {1, 261}, {1, 816}, {2, 249}, {2, 298}};
    int shown = 0;
    for (const auto& [seed, trial] : found) {
      hs::test::DefectCase c = hs::test::defectCase(seed, trial);
      c.options.lodLevels = 0;
      c.options.error.samplesPerFace = 10;
      size_t flips[3];  // decimated only; refined without the guard; refined
      for (int mode = 0; mode < 3; ++mode) {
        ProcessOptions o = c.options;
        o.refine = mode > 0;
        o.refinement.keepFacingOriginal = mode == 2;
        const ProcessResult r = processMesh(c.in, o);
        QVERIFY2(r.ok(), c.where.c_str());
        flips[mode] = r.report.error.flippedNormals;
      }
      qInfo("%s: flipped faces %zu decimated, %zu refined without the guard, %zu with it", c.where.c_str(), flips[0],
            flips[1], flips[2]);
      QVERIFY2(flips[2] <= flips[0], c.where.c_str());
      shown += flips[1] > flips[0];
    }
    QVERIFY2(shown >= 1, "no case turns a face over without the guard any more: find new ones (see the comment)");
  }

  // Locked input vertices keep their place; the result is the same for
  // any thread count.
  void lockedVerticesStayAndThreadsDoNotMatter() {
    // At 90% most result vertices are input vertices left where they were.
    const MeshData in = hs::test::quadScanPatch(40, 10.0, 0.6, 0.001);
    DecimateOptions d;
    d.targetRatio = 0.9;
    const DecimateResult dr = decimate(in, d);
    QVERIFY(dr.ok());
    const ErrorMeter meter(in);
    MeshData one = dr.mesh, two = dr.mesh;
    RefineOptions o;
    o.threads = 1;
    const RefineReport r1 = refineMaxError(meter, one, o);
    o.threads = 2;
    refineMaxError(meter, two, o);
    QCOMPARE(one.positions, two.positions);
    QVERIFY(r1.moved > 0);
    // Lock every input vertex the first run moved a result vertex off.
    std::vector<uint8_t> locked(in.positions.size(), 0);
    size_t lockedCount = 0;
    for (size_t v = 0; v < one.positions.size(); ++v) {
      if (one.positions[v] == dr.mesh.positions[v]) continue;
      for (size_t i = 0; i < in.positions.size(); ++i)
        if (in.positions[i] == dr.mesh.positions[v]) locked[i] = 1, ++lockedCount;
    }
    QVERIFY(lockedCount > 0);  // moved vertices that were input vertices
    MeshData held = dr.mesh;
    o.lockedOriginalVertices = locked;
    refineMaxError(meter, held, o);
    for (size_t v = 0; v < held.positions.size(); ++v)
      for (size_t i = 0; i < in.positions.size(); ++i)
        if (locked[i] && in.positions[i] == dr.mesh.positions[v]) QCOMPARE(held.positions[v], dr.mesh.positions[v]);
  }

  // Through processMesh: on by default, reported, off on request, and the
  // import's maximum error still met.
  void processMeshRefinesUnlessAsked() {
    const MeshData in = hs::test::quadScanPatch(40, 10.0, 0.6, 0.001);
    ProcessOptions o;
    o.decimate = true;
    o.decimation.targetRatio = 0.5;
    const ProcessResult on = processMesh(in, o);
    o.refine = false;
    const ProcessResult off = processMesh(in, o);
    QVERIFY(on.ok() && off.ok());
    QVERIFY(on.report.refined && !off.report.refined);
    QVERIFY(on.report.refinement.moved > 0);
    QVERIFY(on.report.error.hausdorff < off.report.error.hausdorff);
    QCOMPARE(on.mesh.triangleCount(), off.mesh.triangleCount());
  }
};

QTEST_GUILESS_MAIN(TestMeshprocRefine)
#include "test_meshproc_refine.moc"
