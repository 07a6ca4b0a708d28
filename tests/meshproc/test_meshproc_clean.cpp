// Cleaning: every kind of bad input is removed, quarantined, welded or
// split, counted, and named in plain words; nothing is dropped silently.
#include <QtTest>

#include <map>
#include <random>

#include "mesh/nonmanifold_split.h"
#include "mesh/radix_sort.h"
#include "mesh/weld.h"
#include "meshproc/decimate.h"
#include "meshproc/mesh_clean.h"
#include "mesh_builders.h"

using namespace hs::mesh;

namespace {

bool anyWarning(const CleanReport& r, const std::string& a, const std::string& b = "") {
  for (const auto& w : r.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

std::string joined(const CleanReport& r) {
  std::string s;
  for (const auto& w : r.warnings) s += w + "\n";
  return s;
}

MeshData quadSoup() {
  // A unit quad as two triangles with six vertices (two exact duplicates).
  MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 3, 4, 5};
  return m;
}

}  // namespace

class TestMeshprocClean : public QObject {
  Q_OBJECT

 private slots:
  void weldsExactDuplicates() {
    MeshData m = quadSoup();
    CleanReport r;
    std::string err;
    QVERIFY2(cleanMesh(m, {}, r, err), err.c_str());
    QCOMPARE(m.vertexCount(), size_t(4));
    QCOMPARE(m.triangleCount(), size_t(2));
    QCOMPARE(r.duplicateVerticesWelded, size_t(2));
    QVERIFY(anyWarning(r, "2 exact duplicate vertices"));
    // Same position but different UV is a seam, not a duplicate.
    MeshData s = quadSoup();
    s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0.5f, 0}, {1, 1}, {0, 1}};
    CleanReport rs;
    QVERIFY(cleanMesh(s, {}, rs, err));
    QCOMPARE(s.vertexCount(), size_t(5));
  }

  // The decimator's sort-based welds give the same ids as the hash-based
  // weldMap, for any number of threads (first-occurrence order).
  void weldsAgreeForAnyThreadCount() {
    MeshData m = hs::test::curvedGrid(60, 10.0, 0.3, true);
    for (size_t i = 0; i < m.vertexCount(); i += 5) {  // exact duplicates, some with another UV
      m.positions.push_back(m.positions[i]);
      m.uvs.push_back(m.uvs[(i * 13) % m.uvs.size()]);
    }
    uint32_t np = 0, nw = 0;
    const auto pos = weldMap(m.positions, {}, {}, np, 1);
    const auto wedge = weldMap(m.positions, m.uvs, {}, nw, 1);
    QVERIFY(np < nw && nw < m.vertexCount());
    for (unsigned threads : {1u, 2u, 3u}) {
      uint32_t a = 0;
      QVERIFY(weldMap(m.positions, m.uvs, {}, a, threads) == wedge);
      const PositionWedgeWeld w = weldPositionsAndWedges(m.positions, m.uvs, threads);
      QCOMPARE(w.positionCount, np);
      QCOMPARE(w.wedgeCount, nw);
      QVERIFY(w.posOf == pos);
      QVERIFY(w.wedgeOf == wedge);
      // Each id's first vertex: the smallest vertex index with that id.
      std::vector<uint32_t> posFirst(np, UINT32_MAX), wedgeFirst(nw, UINT32_MAX);
      for (size_t v = m.vertexCount(); v-- > 0;) posFirst[pos[v]] = uint32_t(v), wedgeFirst[wedge[v]] = uint32_t(v);
      QVERIFY(w.posFirst == posFirst);
      QVERIFY(w.wedgeFirst == wedgeFirst);
    }
  }

  // The parallel paths of the radix sort and of the corner analysis start
  // at 64k items per worker; below that everything runs on one thread.
  // Above it, every thread count must give what one serial pass gives.
  void radixSortIsStableForAnyThreadCount() {
    std::vector<uint64_t> items(300000);
    uint64_t x = 12345;
    for (size_t i = 0; i < items.size(); ++i) {
      x = x * 6364136223846793005ull + 1442695040888963407ull;
      items[i] = (uint64_t(uint32_t(x >> 40) & 0x3fffffffu) << 32) | uint32_t(i);  // 30-bit keys, payload = index
      if (i % 7 == 0 && i > 0) items[i] = (items[i - 1] & 0xffffffff00000000ull) | uint32_t(i);  // equal keys
    }
    std::vector<uint64_t> reference = items;
    std::stable_sort(reference.begin(), reference.end(), [](uint64_t a, uint64_t b) { return (a >> 32) < (b >> 32); });
    for (unsigned threads : {1u, 2u, 3u}) {
      std::vector<uint64_t> sorted = items;
      radixSortByKey(sorted, 30, threads);
      QVERIFY2(sorted == reference, qPrintable(QString("threads %1").arg(threads)));
    }
  }

  void cornerTwinsAgreeWithABruteForceForAnyThreadCount() {
    MeshData m = hs::test::curvedGrid(400, 10.0, 0.3, false);  // 160,801 vertices
    const uint32_t nv = uint32_t(m.vertexCount());
    // A fin on the edge of the first face (three faces on one edge) and a
    // face with a repeated id (ignored).
    m.positions.push_back({0.0f, 0.0f, 5.0f});
    m.indices.insert(m.indices.end(), {m.indices[0], m.indices[1], nv, 5, 5, 6});
    const uint32_t n = nv + 1;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> directed;
    auto validFace = [&](size_t f) {
      const uint32_t a = m.indices[f * 3], b = m.indices[f * 3 + 1], c = m.indices[f * 3 + 2];
      return a != b && b != c && a != c;
    };
    for (uint32_t c = 0; c < m.indices.size(); ++c)
      if (validFace(c / 3)) directed[{m.indices[c], m.indices[nextCorner(c)]}].push_back(c);
    std::vector<uint32_t> twin(m.indices.size(), kNoCorner);
    size_t boundary = 0;
    for (const auto& [edge, corners] : directed) {
      const auto back = directed.find({edge.second, edge.first});
      const size_t backs = back == directed.end() ? 0 : back->second.size();
      if (corners.size() == 1 && backs == 1) twin[corners[0]] = back->second[0];
      if (corners.size() == 1 && backs == 0) ++boundary;
    }
    for (unsigned threads : {1u, 2u, 3u}) {
      const CornerTopology t = analyzeCorners(m.indices, n, threads);
      QVERIFY2(std::equal(t.twin.begin(), t.twin.end(), twin.begin(), twin.end()), qPrintable(QString("threads %1").arg(threads)));
      QCOMPARE(t.boundaryEdges, boundary);
      QCOMPARE(t.nonManifoldEdges, size_t(1));
    }
  }

  void nonManifoldSplitRewritesOnlyTheDefectsFans() {
    MeshData m = hs::test::curvedGrid(200, 10.0, 0.3, false);  // 40,401 vertices
    const uint32_t nv = uint32_t(m.vertexCount());
    const std::vector<uint32_t> grid = m.indices;
    // Interior vertices away from the border and from each other.
    const size_t f0 = 2 * (50 * 200 + 50), f1 = 2 * (120 * 200 + 130), f2 = 2 * (170 * 200 + 20);
    const uint32_t a = grid[f0 * 3], b = grid[f0 * 3 + 1], v = grid[f1 * 3], w = grid[f2 * 3];
    std::vector<uint32_t> tris = grid;
    // A fin along a -> b (three faces on the edge), a triangle touching the
    // grid at v only (a bow-tie) and a face that repeats w (no fan).
    tris.insert(tris.end(), {a, b, nv, v, nv + 1, nv + 2, w, w, nv + 3});
    const uint32_t n = nv + 4;
    std::vector<uint32_t> firstUse(n, UINT32_MAX);
    for (size_t c = tris.size(); c-- > 0;) firstUse[tris[c]] = uint32_t(c);

    std::vector<uint32_t> reference;
    for (unsigned threads : {1u, 2u, 3u}) {
      const QString where = QString("threads %1").arg(threads);
      std::vector<uint32_t> out = tris, copiedFrom;
      CornerTopology topo = analyzeCorners(out, n, threads);
      QVERIFY(!topo.manifold());
      const NonManifoldSplitStats s = splitNonManifold(out, n, copiedFrom, topo, threads);
      QCOMPARE(s.nonManifoldEdges, size_t(1));
      QCOMPARE(s.nonManifoldVertices, size_t(1));  // v; the repeated face is not a fan
      // The fin's a and b (the grid keeps them), v's extra triangle, w's two
      // corners in the face that repeats it: one copy each.
      QCOMPARE(s.verticesAdded, size_t(5));
      QCOMPARE(copiedFrom, (std::vector<uint32_t>{a, b, v, w, w}));
      // Manifold now, and the topology handed back is the result's.
      const CornerTopology fresh = analyzeCorners(out, n + uint32_t(copiedFrom.size()), 1);
      QVERIFY2(fresh.manifold(), qPrintable(where));
      QVERIFY(std::equal(topo.twin.begin(), topo.twin.end(), fresh.twin.begin(), fresh.twin.end()));
      QCOMPARE(topo.boundaryEdges, fresh.boundaryEdges);
      // The face that repeats w becomes a face once w's corners get copies,
      // which only a second whole-mesh analysis counts.
      QCOMPARE(s.wholeMeshAnalyses, size_t(2));
      // Every corner names the vertex it named or a copy of it; only the
      // defects' vertices are rewritten, and each keeps its first corner.
      for (size_t c = 0; c < out.size(); ++c) {
        const uint32_t source = out[c] < n ? out[c] : copiedFrom[out[c] - n];
        QCOMPARE(source, tris[c]);
        if (out[c] != tris[c]) QVERIFY2(source == a || source == b || source == v || source == w, qPrintable(where));
      }
      for (uint32_t u = 0; u < n; ++u) QCOMPARE(out[firstUse[u]], u);
      QVERIFY(std::equal(out.begin(), out.begin() + grid.size(), grid.begin()));  // the grid's own corners untouched
      if (reference.empty()) reference = out;
      QVERIFY2(out == reference, qPrintable(where));
    }
  }

  // A split that leaves the mesh manifold is confirmed on the corners it
  // rewrote, not by a second analysis of the whole mesh; the topology it
  // hands back must still be exactly what that analysis finds. Random
  // defects of every kind on a grid, against analyzeCorners of the result.
  void aSplitIsConfirmedWhereItWroteAndAgreesWithAFreshAnalysis() {
    const MeshData grid = hs::test::curvedGrid(10, 10.0, 0.3, false);  // 121 vertices, 200 faces: defects meet
    const uint32_t nv = uint32_t(grid.vertexCount());
    const size_t gridFaces = grid.triangleCount();
    std::mt19937 rng(7);
    size_t confirmedLocally = 0, analysedAgain = 0;
    for (int trial = 0; trial < 400; ++trial) {
      std::vector<uint32_t> tris = grid.indices;
      uint32_t n = nv;
      const int defects = 1 + trial % 8;
      for (int d = 0; d < defects; ++d) {
        const size_t f = rng() % gridFaces;
        const uint32_t k = rng() % 3;
        const uint32_t a = grid.indices[f * 3 + k], b = grid.indices[f * 3 + (k + 1) % 3],
                       c = grid.indices[f * 3 + (k + 2) % 3];
        switch ((trial + d) % 5) {
          case 0: tris.insert(tris.end(), {a, b, n++}); break;           // a fin: a third face on a -> b
          case 1: tris.insert(tris.end(), {b, a, n++}); break;           // a fin the other way round
          case 2: tris.insert(tris.end(), {a, n, n + 1}), n += 2; break;  // a bow-tie at a
          case 3: tris.insert(tris.end(), {a, b, c}); break;             // the face twice
          case 4: tris.insert(tris.end(), {a, c, b}); break;             // the face twice, flipped
        }
      }
      for (unsigned threads : {1u, 2u}) {
        const QString where = QString("trial %1, threads %2").arg(trial).arg(threads);
        std::vector<uint32_t> out = tris, copiedFrom;
        CornerTopology topo;
        const NonManifoldSplitStats s = splitNonManifold(out, n, copiedFrom, topo, threads);
        if (s.nonManifoldEdges + s.nonManifoldVertices == 0) {  // a fin on a border edge only extends the grid
          QCOMPARE(s.wholeMeshAnalyses, size_t(1));
          QCOMPARE(s.verticesAdded, size_t(0));
        }
        const CornerTopology fresh = analyzeCorners(out, n + uint32_t(copiedFrom.size()), 1);
        QVERIFY2(fresh.manifold() && topo.manifold(), qPrintable(where));
        QVERIFY2(std::equal(topo.twin.begin(), topo.twin.end(), fresh.twin.begin(), fresh.twin.end()),
                 qPrintable(where));
        QCOMPARE(topo.boundaryEdges, fresh.boundaryEdges);
        QCOMPARE(topo.nonManifoldEdges, size_t(0));
        QCOMPARE(topo.nonManifoldVertices, size_t(0));
        if (threads == 1) (s.wholeMeshAnalyses == 1 ? confirmedLocally : analysedAgain) += 1;
      }
    }
    // Both ways were taken: most splits are confirmed locally, and faces
    // glued along a fold on both ends (the doubled faces) need a further
    // round.
    QVERIFY2(confirmedLocally >= 300, qPrintable(QString::number(confirmedLocally)));
    QVERIFY2(analysedAgain >= 3, qPrintable(QString::number(analysedAgain)));
  }

  // A sliver fin on an edge (a scan's splinter: a third face on the edge,
  // its free vertex a millimetre from one end) must be what comes off,
  // whatever the face order: paired by corner order, a fin listed first
  // took the place of the surface's own face across the edge, which the
  // next round detached, leaving a hole in the surface.
  void aSliverFinComesOffNotTheSurfaceFace() {
    const MeshData grid = hs::test::curvedGrid(14, 10.0, 0.3, false);
    const uint32_t nv = uint32_t(grid.vertexCount());
    const size_t gridBorder = analyzeCorners(grid.indices, nv).boundaryEdges;
    int edges = 0;
    for (size_t f = 0; f < grid.triangleCount(); f += 7)
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t a = grid.indices[f * 3 + k], b = grid.indices[f * 3 + (k + 1) % 3];
        for (bool finFirst : {true, false}) {
          std::vector<uint32_t> tris;
          if (finFirst) tris.insert(tris.end(), {a, b, nv});
          tris.insert(tris.end(), grid.indices.begin(), grid.indices.end());
          if (!finFirst) tris.insert(tris.end(), {a, b, nv});
          std::vector<uint32_t> copiedFrom;
          CornerTopology topo;
          const NonManifoldSplitStats s = splitNonManifold(tris, nv + 1, copiedFrom, topo, 2);
          const QString where = QString("face %1, edge %2, fin %3").arg(f).arg(k).arg(finFirst ? "first" : "last");
          if (s.nonManifoldEdges == 0) continue;  // a border edge: the fin only extends the surface
          ++edges;
          QCOMPARE(s.facesDetached, size_t(0));
          // The surface whole (its own border only) and the fin apart (its three edges).
          QVERIFY2(topo.boundaryEdges == gridBorder + 3,
                   qPrintable(where + QString(": %1 boundary edges, not %2").arg(topo.boundaryEdges).arg(gridBorder + 3)));
        }
      }
    QVERIFY(edges > 100);
  }

  void nanCoordinatesAreQuarantined() {
    MeshData m = hs::test::curvedGrid(4, 1.0, 0.0, false);
    const size_t faces = m.triangleCount();
    m.positions[7] = glm::vec3(NAN, 0, 0);
    m.positions[8].z = INFINITY;
    CleanReport r;
    std::string err;
    QVERIFY2(cleanMesh(m, {}, r, err), err.c_str());
    QCOMPARE(r.nonFiniteVertices, size_t(2));
    QVERIFY(r.facesOnNonFiniteVertices > 0);
    QCOMPARE(m.triangleCount(), faces - r.facesOnNonFiniteVertices);
    QCOMPARE(r.nonFiniteVertexIndices, (std::vector<uint32_t>{7, 8}));
    QVERIFY2(anyWarning(r, "NaN or infinite", "first: 7, 8"), joined(r).c_str());
    for (const auto& p : m.positions) QVERIFY(std::isfinite(p.x + p.y + p.z));
  }

  void indicesOutOfRangeAreQuarantined() {
    MeshData m = hs::test::curvedGrid(4, 1.0, 0.0, false);
    m.indices[3 * 5 + 1] = 100000;
    CleanReport r;
    std::string err;
    QVERIFY(cleanMesh(m, {}, r, err));
    QCOMPARE(r.outOfRangeFaces, size_t(1));
    QCOMPARE(r.outOfRangeFaceIndices, (std::vector<uint32_t>{5}));
    QVERIFY2(anyWarning(r, "past the end of the vertex list", "first face: 5"), joined(r).c_str());
    QCOMPARE(m.triangleCount(), size_t(31));
  }

  void bowTieVerticesAreSplitNotDropped() {
    // Two triangles meeting in one vertex only.
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    m.indices = {0, 1, 2, 0, 3, 4};
    CleanReport r;
    std::string err;
    QVERIFY(cleanMesh(m, {}, r, err));
    QCOMPARE(m.triangleCount(), size_t(2));
    QCOMPARE(r.nonManifoldVertices, size_t(1));
    QCOMPARE(r.verticesAddedBySplit, size_t(1));
    QCOMPARE(m.vertexCount(), size_t(6));
    QVERIFY(analyzeCorners(m.indices, uint32_t(m.vertexCount())).manifold());
    QVERIFY2(anyWarning(r, "bow-tie"), joined(r).c_str());
  }

  void edgesWithThreeFacesAreSplitNotDropped() {
    // A fin: three triangles on the edge (0,1).
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
    m.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    CleanReport r;
    std::string err;
    QVERIFY(cleanMesh(m, {}, r, err));
    QCOMPARE(m.triangleCount(), size_t(3));
    QCOMPARE(r.nonManifoldEdges, size_t(1));
    QVERIFY(r.verticesAddedBySplit >= 2);
    QVERIFY(analyzeCorners(m.indices, uint32_t(m.vertexCount())).manifold());
    QVERIFY2(anyWarning(r, "non-manifold edges"), joined(r).c_str());
    // And the decimator takes it (it splits again at position level).
    MeshData raw;
    raw.positions = m.positions;
    raw.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    DecimateOptions o;
    o.targetTriangles = 2;
    const DecimateResult d = decimate(raw, o);
    QVERIFY2(d.ok(), d.error.c_str());
    QCOMPARE(d.report.nonManifold.nonManifoldEdges, size_t(1));
  }

  void degenerateAndDuplicateFacesAreRemoved() {
    MeshData m = hs::test::curvedGrid(4, 1.0, 0.0, false);
    const size_t faces = m.triangleCount();
    m.indices.insert(m.indices.end(), {0, 0, 1});                // repeated index
    // Three vertices along the grid's first row: collinear, zero area.
    std::vector<uint32_t> row;
    for (uint32_t v = 0; v < m.vertexCount(); ++v)
      if (m.positions[v].y == 0.0f) row.push_back(v);
    QVERIFY(row.size() >= 3);
    m.indices.insert(m.indices.end(), {row[0], row[1], row[2]});
    m.indices.insert(m.indices.end(), {m.indices[3], m.indices[4], m.indices[5]});  // duplicate face
    m.submeshes = {{0, uint32_t(m.indices.size()), -1}};
    CleanReport r;
    std::string err;
    QVERIFY(cleanMesh(m, {}, r, err));
    QCOMPARE(r.repeatedIndexFaces, size_t(1));
    QCOMPARE(r.zeroAreaFaces, size_t(1));
    QCOMPARE(r.duplicateFaces, size_t(1));
    QCOMPARE(m.triangleCount(), faces);
    QVERIFY2(anyWarning(r, "zero area"), joined(r).c_str());
  }

  void allDegenerateIsRefusedWithAMessage() {
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    m.indices = {0, 1, 2, 1, 2, 3, 0, 0, 3};
    CleanReport r;
    std::string err;
    QVERIFY(!cleanMesh(m, {}, r, err));
    QVERIFY2(err.find("every face was removed") != std::string::npos && err.find("3 degenerate") != std::string::npos,
             err.c_str());
    QCOMPARE(r.zeroAreaFaces + r.repeatedIndexFaces, size_t(3));
  }

  void noFacesIsRefusedWithAMessage() {
    MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}};
    CleanReport r;
    std::string err;
    QVERIFY(!cleanMesh(m, {}, r, err));
    QVERIFY2(err.find("no faces") != std::string::npos && err.find("2 vertices") != std::string::npos, err.c_str());
  }

  void submeshesAndMaterialsSurvive() {
    MeshData m = hs::test::curvedGrid(4, 1.0, 0.0, false);
    m.materials.resize(2);
    const uint32_t half = uint32_t(m.indices.size() / 2);
    m.submeshes = {{0, half, 1}, {half, half, 0}};
    m.indices[0] = m.indices[1];  // one degenerate face in the first submesh
    CleanReport r;
    std::string err;
    QVERIFY(cleanMesh(m, {}, r, err));
    QCOMPARE(m.submeshes.size(), size_t(2));
    QCOMPARE(m.submeshes[0].material, 1);
    QCOMPARE(m.submeshes[0].indexCount, half - 3);
    QCOMPARE(m.submeshes[1].firstIndex, half - 3);
  }
};

QTEST_GUILESS_MAIN(TestMeshprocClean)
#include "test_meshproc_clean.moc"
