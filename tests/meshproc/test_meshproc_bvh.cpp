// The BVH's segment-occlusion query (meshproc/closest_point_bvh.h), which
// the shadow benchmark and the renderer's shadow test use as their CPU ray
// cast, against brute force over every triangle.
#include <QtTest>

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
