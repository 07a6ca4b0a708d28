// The BVH's queries (meshproc/closest_point_bvh.h) against brute force over
// every triangle: the segment-occlusion query, which the shadow benchmark
// and the renderer's shadow test use as their CPU ray cast, and the
// grouped closest-point query the error report makes per face.
#include <QtTest>

#include <algorithm>
#include <random>

#include "meshproc/closest_point_bvh.h"
#include "mesh_builders.h"

using namespace hs;
using namespace hs::mesh;
using hs::test::curvedGrid;
using hs::test::icosphere;

namespace {

// Moller-Trumbore over every triangle, written apart from the BVH's.
bool bruteOccluded(const MeshData& m, const glm::dvec3& o, const glm::dvec3& d, double tMin, double tMax) {
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    const glm::dvec3 a(m.positions[m.indices[f * 3]]), b(m.positions[m.indices[f * 3 + 1]]),
        c(m.positions[m.indices[f * 3 + 2]]);
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) continue;
    const glm::dvec3 s = o - a, q = glm::cross(s, e1);
    const double u = glm::dot(s, p) / det, v = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && t >= tMin && t <= tMax) return true;
  }
  return false;
}

// The least squared distance over every triangle and the lowest face that
// has it (closestPointOnTriangle is the one exact test; what is checked
// is that the tree finds its minimum).
std::pair<double, uint32_t> bruteClosest(const MeshData& m, const glm::dvec3& q) {
  double best = HUGE_VAL;
  uint32_t face = UINT32_MAX;
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    glm::dvec3 p, bary;
    const double d = closestPointOnTriangle(q, glm::dvec3(m.positions[m.indices[f * 3]]),
                                            glm::dvec3(m.positions[m.indices[f * 3 + 1]]),
                                            glm::dvec3(m.positions[m.indices[f * 3 + 2]]), p, bary);
    if (d < best) best = d, face = uint32_t(f);
  }
  return {best, face};
}

}  // namespace

class TestMeshprocBvh : public QObject {
  Q_OBJECT
 private slots:
  // Random segments into and around a sphere and a wavy grid: the BVH
  // answers as brute force does, with both answers well represented.
  void occlusionMatchesBruteForce() {
    for (const MeshData& m : std::vector<MeshData>{icosphere(3, 1.0), curvedGrid(40, 4.0, 0.3, false)}) {
      const ClosestPointBvh bvh(m);
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> u(-3.0, 3.0), near(-1.3, 1.3);
      int hits = 0, misses = 0, disagree = 0;
      for (int i = 0; i < 4000; ++i) {
        const glm::dvec3 o(u(rng), u(rng), u(rng));
        // Aimed at a point around the mesh, stopping at it or halfway.
        const glm::dvec3 d = glm::dvec3(near(rng), near(rng), near(rng)) - o;
        const double tMax = i % 2 ? 1.0 : 0.5;
        const bool a = bvh.occluded(o, d, 1e-9, tMax), b = bruteOccluded(m, o, d, 1e-9, tMax);
        disagree += a != b;
        (b ? hits : misses)++;
      }
      qInfo("%d hits, %d misses, %d disagreements", hits, misses, disagree);
      QVERIFY(hits > 200 && misses > 200);
      // Only a ray grazing an edge may fall either way (rounding): none in 4000.
      QCOMPARE(disagree, 0);
    }
  }

  // Groups of points as the error report asks them (a face's samples):
  // every hit is the one closest() gives for that point alone, bit for bit,
  // and the brute-force minimum with its lowest face. Chunks small and
  // near the surface take the collected-leaves path, spread ones (more
  // than kMaxLeaves leaves near them) a walk per point; groups of more
  // than one chunk, far groups, single points, repeated points and points
  // on shared edges of a flat grid (ties between two faces at distance 0)
  // are among them.
  void closestManyMatchesClosestAndBruteForce() {
    const std::vector<MeshData> targets = {icosphere(3, 1.0), curvedGrid(40, 4.0, 0.3, false),
                                           curvedGrid(4, 4.0, 0.3, false), curvedGrid(12, 4.0, 0.0, false)};
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int groups = 0, points = 0, single = 0, walked = 0, scanned = 0;
    for (size_t t = 0; t < targets.size(); ++t) {
      const MeshData& m = targets[t];
      const ClosestPointBvh bvh(m);
      ClosestPointBvh::ManyScratch scratch;
      uint32_t hint = UINT32_MAX;
      for (int g = 0; g < 120; ++g) {
        // Spread: 0.02 (a small face) up to 3 (most of the mesh); centre on,
        // near or far from the surface.
        const double spread = g % 4 == 0 ? 3.0 : g % 4 == 1 ? 0.6 : 0.02;
        const double away = g % 5 == 0 ? 40.0 : g % 5 == 1 ? 0.5 : 0.02;
        const size_t n = g % 7 == 0 ? 1 : g % 7 == 1 ? 300 : size_t(2 + g % 23);
        const glm::dvec3 centre(m.positions[size_t(g * 37) % m.positions.size()]);
        std::vector<glm::dvec3> group(n);
        for (size_t k = 0; k < n; ++k)
          group[k] = centre + spread * glm::dvec3(u(rng), u(rng), 0.2 * u(rng)) + glm::dvec3(0, 0, away * u(rng));
        if (n > 3) group[2] = group[1];  // a repeated point
        if (t == 3 && n > 2) {
          // On the flat grid: points on the edges between faces (z = 0,
          // x or y on a grid line), where two faces are at distance 0.
          const double cell = 4.0 / 12.0;
          group[0] = glm::dvec3(-2.0 + cell * double(g % 12), -2.0 + cell * (0.5 + double(g % 11)), 0.0);
          group[1] = glm::dvec3(-2.0 + cell * (0.5 + double(g % 11)), -2.0 + cell * double(g % 12), 0.0);
        }
        std::vector<ClosestPointBvh::Hit> hits(n);
        const size_t walkedBefore = scratch.walkedChunks, scannedBefore = scratch.scannedChunks;
        hint = bvh.closestMany(group, hint, hits, scratch);
        for (size_t k = 0; k < n; ++k) {
          const auto one = bvh.closest(group[k]);
          const auto [bruteD, bruteF] = bruteClosest(m, group[k]);
          QCOMPARE(hits[k].distanceSq, one.distanceSq);
          QCOMPARE(hits[k].face, one.face);
          QVERIFY(hits[k].point == one.point);
          QVERIFY(hits[k].bary == one.bary);
          QCOMPARE(hits[k].distanceSq, bruteD);
          QCOMPARE(hits[k].face, bruteF);
        }
        // The hint handed on is one of the group's faces.
        QVERIFY(std::any_of(hits.begin(), hits.end(), [&](const auto& h) { return h.face == hint; }));
        single += n == 1;
        walked += scratch.walkedChunks > walkedBefore;
        scanned += scratch.scannedChunks > scannedBefore;
        ++groups, points += int(n);
      }
    }
    qInfo("%d groups, %d points: %d single, %d walked point by point, %d through collected leaves", groups, points,
          single, walked, scanned);
    QVERIFY(walked >= 20 && scanned >= 100);
    // No group at all: nothing asked, the hint passes through.
    const ClosestPointBvh bvh(icosphere(1, 1.0));
    ClosestPointBvh::ManyScratch scratch;
    QCOMPARE(bvh.closestMany({}, 5u, {}, scratch), 5u);
    // An empty tree finds nothing.
    std::vector<glm::dvec3> one = {glm::dvec3(0.0)};
    std::vector<ClosestPointBvh::Hit> hit(1);
    ClosestPointBvh().closestMany(one, UINT32_MAX, hit, scratch);
    QVERIFY(!hit[0].found());
  }

  // closestUnless() against brute force: a distance at least the stop is
  // exact (the same face as closest()), one below it is an upper bound
  // still below the stop; both cases well represented, with and without a
  // hint, and a stop of 0 (never stops) is closest() itself.
  void closestUnlessIsExactFromItsStop() {
    const MeshData m = curvedGrid(30, 4.0, 0.3, false);
    const ClosestPointBvh bvh(m);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int exact = 0, early = 0, shortened = 0;
    uint32_t hint = UINT32_MAX;
    for (int i = 0; i < 2000; ++i) {
      // Near the surface (a vertex, moved by up to 0.2 across and 0.3 up
      // or down); stops up to 0.15 away.
      const glm::dvec3 q = glm::dvec3(m.positions[size_t(i * 7919) % m.positions.size()]) +
                           glm::dvec3(0.2 * u(rng), 0.2 * u(rng), 0.3 * u(rng));
      const double stop = i % 3 == 0 ? 0.0 : 0.075 * (u(rng) + 1.0);
      const double stopSq = stop * stop;
      const auto [bruteD, bruteF] = bruteClosest(m, q);
      const auto h = bvh.closestUnless(q, i % 2 ? hint : UINT32_MAX, stopSq);
      if (bruteD >= stopSq) {
        QCOMPARE(h.distanceSq, bruteD);
        QCOMPARE(h.face, bruteF);
        ++exact;
      } else {
        QVERIFY(h.distanceSq < stopSq && h.distanceSq >= bruteD);
        QVERIFY(h.found());
        ++early, shortened += h.distanceSq > bruteD;
      }
      hint = h.face;
    }
    qInfo("%d exact, %d below the stop (%d of them an upper bound above the least)", exact, early, shortened);
    QVERIFY(exact > 300 && early > 300 && shortened > 20);
  }

  // Axis-aligned directions (zero components: the slab test's division by
  // zero) and the interval's ends.
  void axisRaysAndInterval() {
    const MeshData m = icosphere(2, 1.0);
    const ClosestPointBvh bvh(m);
    QVERIFY(bvh.occluded({0, 0, -5}, {0, 0, 1}, 0.0, 10.0));
    QVERIFY(!bvh.occluded({0, 0, -5}, {0, 0, 1}, 0.0, 3.5));   // stops before the sphere
    QVERIFY(!bvh.occluded({0, 0, -5}, {0, 0, -1}, 0.0, 10.0)); // points away
    QVERIFY(!bvh.occluded({3, 0, -5}, {0, 0, 1}, 0.0, 10.0));  // passes beside it
    QVERIFY(bvh.occluded({0, -5, 0.2}, {0, 1, 0}, 0.0, 10.0));
    QVERIFY(!ClosestPointBvh().occluded({0, 0, 0}, {0, 0, 1}, 0.0, 1.0));  // empty tree
  }
};

QTEST_GUILESS_MAIN(TestMeshprocBvh)
#include "test_meshproc_bvh.moc"
