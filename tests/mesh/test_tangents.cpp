// mesh::computeTangents: MikkTSpace's definition on small meshes whose
// tangents are known by hand, and the cases it must survive (mirrored UVs,
// degenerate triangles, missing UVs, a sphere's poles) with finite, unit,
// perpendicular tangents.
#include <QtTest>

#include <cmath>

#include "mesh/primitives.h"
#include "mesh/tangents.h"

using namespace hs;

namespace {

// Two triangles of a unit quad in the XY plane (normal +Z) with the UVs given per corner.
mesh::MeshData quad(glm::vec2 uv0, glm::vec2 uv1, glm::vec2 uv2, glm::vec2 uv3) {
  mesh::MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.uvs = {uv0, uv1, uv2, uv3};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.submeshes.push_back({0, 6, -1});
  return m;
}

bool near(const glm::vec4& a, const glm::vec4& b, float eps = 1e-5f) {
  return glm::all(glm::lessThan(glm::abs(a - b), glm::vec4(eps)));
}

QString str(const glm::vec4& v) { return QString("(%1, %2, %3, %4)").arg(v.x).arg(v.y).arg(v.z).arg(v.w); }

void checkSound(const mesh::MeshData& m, const std::vector<glm::vec4>& t) {
  QCOMPARE(t.size(), m.positions.size());
  for (size_t i = 0; i < t.size(); ++i) {
    const glm::vec3 xyz(t[i]);
    QVERIFY2(std::isfinite(t[i].x) && std::isfinite(t[i].y) && std::isfinite(t[i].z), qPrintable(str(t[i])));
    QVERIFY2(std::abs(glm::length(xyz) - 1.0f) < 1e-4f, qPrintable(str(t[i])));
    QVERIFY(t[i].w == 1.0f || t[i].w == -1.0f);
    if (i < m.normals.size() && glm::length(m.normals[i]) > 0.5f)
      QVERIFY2(std::abs(glm::dot(xyz, glm::normalize(m.normals[i]))) < 1e-4f, qPrintable(str(t[i])));
  }
}

}  // namespace

class TestTangents : public QObject {
  Q_OBJECT
 private slots:
  // MikkTSpace's values by its definition: T = dP/du in the tangent plane,
  // w = sign(dot(cross(N, T), dP/dv)).
  void knownValues() {
    // u along +X, v along +Y: T = +X, cross(Z, X) = +Y = dP/dv, w = +1.
    for (const auto& t : mesh::computeTangents(quad({0, 0}, {1, 0}, {1, 1}, {0, 1})))
      QVERIFY2(near(t, {1, 0, 0, 1}), qPrintable(str(t)));
    // v = 0 at the top row (the project's convention): v along -Y, w = -1.
    for (const auto& t : mesh::computeTangents(quad({0, 1}, {1, 1}, {1, 0}, {0, 0})))
      QVERIFY2(near(t, {1, 0, 0, -1}), qPrintable(str(t)));
    // UVs turned a quarter: u along +Y, v along -X: T = +Y, cross(Z, Y) = -X = dP/dv, w = +1.
    for (const auto& t : mesh::computeTangents(quad({0, 1}, {0, 0}, {1, 0}, {1, 1})))
      QVERIFY2(near(t, {0, 1, 0, 1}), qPrintable(str(t)));
    // UVs stretched 4x along u and sheared: T still follows dP/du.
    // u = 4x + y, v = y: dP/du = (1/4, 0, 0), dP/dv = (-1/4, 1, 0).
    for (const auto& t : mesh::computeTangents(quad({0, 0}, {4, 0}, {5, 1}, {1, 1})))
      QVERIFY2(near(t, {1, 0, 0, 1}), qPrintable(str(t)));
    // A tilted normal: the tangent is dP/du made perpendicular to it.
    mesh::MeshData tilted = quad({0, 0}, {1, 0}, {1, 1}, {0, 1});
    const glm::vec3 n = glm::normalize(glm::vec3(1, 0, 1));
    tilted.normals.assign(4, n);
    for (const auto& t : mesh::computeTangents(tilted))
      QVERIFY2(near(t, glm::vec4(glm::normalize(glm::vec3(1, 0, -1)), 1)), qPrintable(str(t)));
  }

  void mirroredUvsKeepEachSidesHandedness() {
    // Two quads side by side sharing the edge x = 1; the right one's u runs
    // back (a mirror), as on a symmetric model's two halves.
    mesh::MeshData m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    m.normals.assign(6, glm::vec3(0, 0, 1));
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}, {0, 1}};
    m.indices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
    m.submeshes.push_back({0, 12, -1});
    const auto t = mesh::computeTangents(m);
    checkSound(m, t);
    QVERIFY2(near(t[0], {1, 0, 0, 1}), qPrintable(str(t[0])));
    QVERIFY2(near(t[3], {1, 0, 0, 1}), qPrintable(str(t[3])));
    // The mirrored side: dP/du = -X, cross(Z, -X) = -Y, dP/dv = +Y: w = -1.
    QVERIFY2(near(t[4], {-1, 0, 0, -1}), qPrintable(str(t[4])));
    QVERIFY2(near(t[5], {-1, 0, 0, -1}), qPrintable(str(t[5])));
    // The seam's vertices take one side's tangent whole (not an average that cancels).
    QVERIFY(near(t[1], {1, 0, 0, 1}) || near(t[1], {-1, 0, 0, -1}));
  }

  void degenerateTrianglesAndMissingUvsStayFinite() {
    mesh::MeshData m = quad({0, 0}, {1, 0}, {1, 1}, {0, 1});
    // A zero-area triangle (a repeated vertex), one with collinear corners,
    // one with zero UV area, and a vertex no triangle uses.
    m.positions.push_back({0.5f, 0.5f, 0});
    m.normals.emplace_back(0, 0, 1);
    m.uvs.emplace_back(0.5f, 0.5f);
    m.positions.push_back({3, 3, 3});
    m.normals.emplace_back(0, 1, 0);
    m.uvs.emplace_back(0, 0);
    m.indices.insert(m.indices.end(), {0, 0, 1, 0, 4, 2, 4, 4, 4});
    auto t = mesh::computeTangents(m);
    checkSound(m, t);
    QVERIFY2(near(t[1], {1, 0, 0, 1}), "the degenerate triangles do not disturb the good ones");
    // No UVs at all: a tangent perpendicular to each normal, the same each time.
    m.uvs.clear();
    t = mesh::computeTangents(m);
    checkSound(m, t);
    QCOMPARE(t, mesh::computeTangents(m));
    // A zero normal and NaN UVs do not make NaN either.
    m = quad({0, 0}, {1, 0}, {1, 1}, {0, 1});
    m.normals[2] = glm::vec3(0.0f);
    m.uvs[3] = glm::vec2(std::nanf(""), 0.0f);
    t = mesh::computeTangents(m);
    for (const auto& x : t) QVERIFY2(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z), qPrintable(str(x)));
  }

  void sphereTangentsFollowLongitude() {
    const mesh::MeshData s = mesh::uvSphere(1.0f, 256, 128);
    const auto t = mesh::computeTangents(s);
    checkSound(s, t);
    // Away from the poles, dP/du points east: (-sin phi, cos phi, 0); v runs
    // south, and cross(N, east) = north = -dP/dv: w = -1. (Each triangle's
    // dP/du is a chord direction: within 0.02 on a fine sphere.)
    for (size_t i = 0; i < s.positions.size(); ++i) {
      const glm::vec3 p = s.positions[i];
      if (std::abs(p.z) > 0.9f) continue;
      const glm::vec3 east = glm::normalize(glm::vec3(-p.y, p.x, 0.0f));
      QVERIFY2(near(t[i], glm::vec4(east, -1.0f), 0.02f), qPrintable(str(t[i])));
    }
  }
};

QTEST_GUILESS_MAIN(TestTangents)
#include "test_tangents.moc"
