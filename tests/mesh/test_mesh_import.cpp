// Mesh import: our OBJ reader against Assimp on the Stanford bunny, up-axis
// conversion, UTM-scale coordinates, every kind of bad input, textures
// through OBJ+MTL, glTF (embedded), FBX and PLY, progress and cancel.
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/image_io.h"
#include "file_bytes.h"
#include "mesh/mesh_import.h"
#include "mesh_fixture_spec.h"

using namespace hs::mesh;
namespace fs = std::filesystem;
namespace fx = hs::test::fixture;

using hs::test::readFile;
using hs::test::writeFile;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";
const std::string kData = HS_TEST_DATA_DIR "/mesh";



std::vector<glm::dvec3> worldPositions(const MeshData& m) {
  std::vector<glm::dvec3> out;
  out.reserve(m.positions.size());
  for (const auto& p : m.positions) out.push_back(m.origin + glm::dvec3(p));
  return out;
}

double surfaceArea(const MeshData& m) {
  const auto w = worldPositions(m);
  double area = 0.0;
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
    area += 0.5 * glm::length(glm::cross(w[m.indices[i + 1]] - w[m.indices[i]], w[m.indices[i + 2]] - w[m.indices[i]]));
  return area;
}

// Nearest-point queries on a point set through a uniform grid.
class PointGrid {
 public:
  PointGrid(const std::vector<glm::dvec3>& pts, double cell) : pts_(pts), cell_(cell) {
    for (size_t i = 0; i < pts.size(); ++i) cells_[key(cellOf(pts[i]))].push_back(i);
  }
  // Distance to the nearest point, searching the 27 cells around `p`
  // (so only distances up to one cell are exact; beyond that: infinity).
  double nearest(const glm::dvec3& p) const {
    const glm::ivec3 c = cellOf(p);
    double best = INFINITY;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (size_t i : it->second) best = std::min(best, glm::length(pts_[i] - p));
        }
    return best;
  }

 private:
  glm::ivec3 cellOf(const glm::dvec3& p) const { return glm::ivec3(glm::floor(p / cell_)); }
  static uint64_t key(const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
           uint64_t(uint32_t(c.z) & 0x1fffff);
  }
  const std::vector<glm::dvec3>& pts_;
  double cell_;
  std::unordered_map<uint64_t, std::vector<size_t>> cells_;
};

// Largest distance from a point of `a` to its nearest point in `b` (within `cell`).
double maxNearestDistance(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, double cell) {
  PointGrid grid(b, cell);
  double worst = 0.0;
  for (const auto& p : a) worst = std::max(worst, grid.nearest(p));
  return worst;
}

bool anyWarningContains(const ImportReport& r, const std::string& a, const std::string& b = {}) {
  for (const auto& w : r.warnings)
    if (w.find(a) != std::string::npos && (b.empty() || w.find(b) != std::string::npos)) return true;
  return false;
}

std::string joinWarnings(const ImportReport& r) {
  std::string s;
  for (const auto& w : r.warnings) s += "\n  " + w;
  return s;
}

ImportOptions withReader(Reader r, UpAxis up = UpAxis::Auto) {
  ImportOptions o;
  o.reader = r;
  o.up = up;
  return o;
}

// Index of the vertex nearest to world point `p`.
size_t vertexNear(const MeshData& m, const glm::dvec3& p) {
  const auto w = worldPositions(m);
  size_t best = 0;
  for (size_t i = 1; i < w.size(); ++i)
    if (glm::length(w[i] - p) < glm::length(w[best] - p)) best = i;
  return best;
}

// The fixture quad's corners in world space (Z-up) after the Y-up to Z-up
// conversion every importer applies: file (x, y, z) -> world (x, -z, y).
std::vector<glm::dvec3> fixtureQuadWorld(double unitScale = 1.0) {
  std::vector<glm::dvec3> out;
  for (const auto& p : fx::kQuadPositions) {
    const glm::dvec3 f = (glm::dvec3(p[0], p[1], p[2]) +
                          glm::dvec3(fx::kNodeTranslation[0], fx::kNodeTranslation[1], fx::kNodeTranslation[2])) *
                         unitScale;
    out.emplace_back(f.x, -f.z, f.y);
  }
  return out;
}

// Checks a mesh against the textured-quad fixture: corners, texture
// coordinates (v = 0 at the image's top row), decoded texels, base colour.
void checkTexturedQuad(const MeshData& m, const glm::vec4& expectedBase, double unitScale = 1.0) {
  QCOMPARE(m.triangleCount(), size_t(2));
  QCOMPARE(m.uvs.size(), m.positions.size());
  const auto corners = fixtureQuadWorld(unitScale);
  const auto world = worldPositions(m);
  for (size_t i = 0; i < corners.size(); ++i) {
    const size_t v = vertexNear(m, corners[i]);
    QVERIFY2(glm::length(world[v] - corners[i]) < 1e-5 * unitScale,
             qPrintable(QString("corner %1 not found").arg(i)));
    // File uv (u, v) with v up from the bottom row -> stored (u, 1 - v).
    const glm::vec2 expected(fx::kQuadUvs[i][0], 1.0f - fx::kQuadUvs[i][1]);
    QVERIFY2(glm::length(m.uvs[v] - expected) < 1e-6f,
             qPrintable(QString("corner %1: uv %2,%3, expected %4,%5")
                            .arg(i).arg(double(m.uvs[v].x)).arg(double(m.uvs[v].y))
                            .arg(double(expected.x)).arg(double(expected.y))));
  }
  // The material the triangles use has the texture and base colour.
  QVERIFY(!m.submeshes.empty());
  const int mi = m.submeshes.front().material;
  QVERIFY(mi >= 0 && size_t(mi) < m.materials.size());
  const Material& mat = m.materials[size_t(mi)];
  for (int c = 0; c < 4; ++c)
    QVERIFY2(std::abs(mat.baseColor[c] - expectedBase[c]) < 1e-5f,
             qPrintable(QString("base colour channel %1: %2, expected %3").arg(c).arg(double(mat.baseColor[c])).arg(double(expectedBase[c]))));
  QVERIFY(mat.diffuseTexture >= 0 && size_t(mat.diffuseTexture) < m.textures.size());
  const Texture& t = m.textures[size_t(mat.diffuseTexture)];
  QCOMPARE(t.width, fx::kTexWidth);
  QCOMPARE(t.height, fx::kTexHeight);
  QCOMPARE(t.rgba.size(), size_t(fx::kTexWidth * fx::kTexHeight * 4));
  for (size_t i = 0; i < fx::kTexels.size(); ++i)
    for (int c = 0; c < 4; ++c) QCOMPARE(int(t.rgba[i * 4 + size_t(c)]), int(fx::kTexels[i][size_t(c)]));
  QVERIFY(!t.encoded.empty());  // the source PNG is kept for the scene file
}

// A synthetic terrain-like OBJ (n x n quads with vt), big enough that the
// reader reports progress while parsing (it does so every 4 MB).
std::string gridObj(int n) {
  std::string s;
  s.reserve(size_t(n + 1) * size_t(n + 1) * 60 + size_t(n) * size_t(n) * 60);
  char buf[128];
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      std::snprintf(buf, sizeof buf, "v %.3f %.3f %.3f\n", 500000.0 + x * 0.5, 4400000.0 + y * 0.5,
                    100.0 + std::sin(x * 0.1) * std::cos(y * 0.07) * 3.0);
      s += buf;
    }
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      std::snprintf(buf, sizeof buf, "vt %.5f %.5f\n", double(x) / n, double(y) / n);
      s += buf;
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
      std::snprintf(buf, sizeof buf, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, a, b, b, c, c, a, a, c, c, d, d);
      s += buf;
    }
  return s;
}

}  // namespace

class TestMeshImport : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }

  // A one-triangle OBJ in `dir` whose material `material` maps `texture`:
  // it imports untextured with a warning naming the texture (and
  // `alsoInWarning`), or, with strictTextures, fails naming the texture.
  void expectTextureProblem(const std::string& dir, const std::string& material, const std::string& texture,
                            const std::string& alsoInWarning) {
    writeFile(dir + "/m.mtl", "newmtl " + material + "\nKd 0.5 0.5 0.5\nmap_Kd " + texture + "\n");
    writeFile(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl " + material +
                                  "\nf 1/1 2/2 3/3\n");
    const ImportResult r = importMesh(dir + "/m.obj");
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(1));
    QVERIFY(r.mesh->textures.empty());
    QCOMPARE(r.mesh->materials.size(), size_t(1));
    QCOMPARE(r.mesh->materials[0].diffuseTexture, -1);
    QVERIFY2(anyWarningContains(r.report, texture, alsoInWarning), joinWarnings(r.report).c_str());

    ImportOptions strict;
    strict.strictTextures = true;
    const ImportResult s = importMesh(dir + "/m.obj", strict);
    QVERIFY(!s.ok());
    QVERIFY2(s.error.find(texture) != std::string::npos, s.error.c_str());
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  // ---- the bunny through both readers -------------------------------------

  void bunnyObjReaderAndAssimpAgree() {
    const ImportResult own = importMesh(kBunny, withReader(Reader::Obj));
    const ImportResult ai = importMesh(kBunny, withReader(Reader::Assimp));
    QVERIFY2(own.ok(), own.error.c_str());
    QVERIFY2(ai.ok(), ai.error.c_str());
    QCOMPARE(own.report.reader, std::string("obj"));
    QCOMPARE(ai.report.reader, std::string("assimp"));

    // The file says how many faces it has; count them independently.
    const std::string text = readFile(kBunny);
    size_t faceLines = 0;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) faceLines += line.rfind("f ", 0) == 0;
    QCOMPARE(faceLines, size_t(69451));
    QCOMPARE(own.mesh->triangleCount(), faceLines);
    QCOMPARE(ai.mesh->triangleCount(), own.mesh->triangleCount());

    // Same positions in world space, both ways, within 1e-6 of the size.
    const auto a = worldPositions(*own.mesh), b = worldPositions(*ai.mesh);
    const double size = glm::length(glm::dvec3(own.mesh->bounds().max - own.mesh->bounds().min));
    QVERIFY(size > 0.1 && size < 1.0);  // the scan is about 0.2 m across
    const double tol = 1e-6 * size;
    const double ab = maxNearestDistance(a, b, tol * 4), ba = maxNearestDistance(b, a, tol * 4);
    qInfo("bunny: %zu vs %zu vertices; largest position difference %.3g m (own->assimp), %.3g m (assimp->own)",
          a.size(), b.size(), ab, ba);
    QVERIFY(ab <= tol);
    QVERIFY(ba <= tol);

    const double areaOwn = surfaceArea(*own.mesh), areaAi = surfaceArea(*ai.mesh);
    qInfo("bunny surface area: own %.9g m2, assimp %.9g m2", areaOwn, areaAi);
    QVERIFY(areaOwn > 0.0);
    QVERIFY(std::abs(areaOwn - areaAi) <= 1e-6 * areaOwn);

    // Neither reader had to drop anything from this clean scan.
    QCOMPARE(own.report.outOfRangeFaces + own.report.nonFiniteVertices + own.report.degenerateFaces, size_t(0));
    QCOMPARE(own.report.trianglesOut, faceLines);
    QVERIFY(own.report.normalsGenerated);  // the file has none
  }

  // ---- up axis --------------------------------------------------------------

  void upAxisYToZ_data() {
    QTest::addColumn<int>("reader");
    QTest::newRow("obj") << int(Reader::Obj);
    QTest::newRow("assimp") << int(Reader::Assimp);
  }
  void upAxisYToZ() {
    QFETCH(int, reader);
    const std::string p = path("tiny_yup.obj");
    // A triangle pointing up the file's +Y (its up axis) from (1, 2, 3).
    writeFile(p, "v 1 2 3\nv 2 2 3\nv 1 5 3\nf 1 2 3\n");
    for (UpAxis up : {UpAxis::Auto, UpAxis::Y, UpAxis::Z}) {
      ImportOptions o = withReader(Reader(reader), up);
      o.recenter = false;
      const ImportResult r = importMesh(p, o);
      QVERIFY2(r.ok(), r.error.c_str());
      const auto w = worldPositions(*r.mesh);
      QCOMPARE(w.size(), size_t(3));
      const bool converted = up != UpAxis::Z;
      QCOMPARE(r.report.upAxisConverted, converted);
      const std::vector<glm::dvec3> file = {{1, 2, 3}, {2, 2, 3}, {1, 5, 3}};
      for (const auto& f : file) {
        // Y-up to Z-up: x stays, file y becomes z, file z becomes -y.
        const glm::dvec3 expected = converted ? glm::dvec3(f.x, -f.z, f.y) : f;
        const size_t v = vertexNear(*r.mesh, expected);
        QVERIFY2(glm::length(w[v] - expected) < 1e-6,
                 qPrintable(QString("(%1,%2,%3) not at (%4,%5,%6)").arg(f.x).arg(f.y).arg(f.z)
                                .arg(expected.x).arg(expected.y).arg(expected.z)));
      }
      // The triangle points up the file's +Y: 3 m tall in world Z once
      // converted, flat at file z = 3 when the file is taken as Z-up.
      double minZ = INFINITY, maxZ = -INFINITY;
      for (const auto& q : w) {
        minZ = std::min(minZ, q.z);
        maxZ = std::max(maxZ, q.z);
      }
      QCOMPARE(maxZ - minZ, converted ? 3.0 : 0.0);
    }
  }

  // ---- large coordinates ----------------------------------------------------

  void utmCoordinatesKeepMillimetres() {
    const std::string p = path("utm.obj");
    // A corner at UTM-like coordinates, neighbours 1 mm away along each axis,
    // and a large triangle so a reader that merges the close ones still has faces.
    const glm::dvec3 base(656059.123, 5514553.456, 1713.789);
    const std::vector<glm::dvec3> written = {
        base,
        base + glm::dvec3(0.001, 0, 0),
        base + glm::dvec3(0, 0.001, 0),
        base + glm::dvec3(0, 0, 0.001),
        base + glm::dvec3(0.001, 0.001, 0.001),
        base + glm::dvec3(10, 0, 0),
        base + glm::dvec3(0, 10, 0),
    };
    std::string text;
    const char* decimals[7][3] = {
        {"656059.123", "5514553.456", "1713.789"}, {"656059.124", "5514553.456", "1713.789"},
        {"656059.123", "5514553.457", "1713.789"}, {"656059.123", "5514553.456", "1713.790"},
        {"656059.124", "5514553.457", "1713.790"}, {"656069.123", "5514553.456", "1713.789"},
        {"656059.123", "5514563.456", "1713.789"}};
    for (auto& d : decimals) text += std::string("v ") + d[0] + " " + d[1] + " " + d[2] + "\n";
    text += "f 1 2 3\nf 1 2 4\nf 2 5 4\nf 3 5 4\nf 1 6 7\n";
    writeFile(p, text);

    const ImportResult own = importMesh(p, withReader(Reader::Obj, UpAxis::Z));
    QVERIFY2(own.ok(), own.error.c_str());
    QCOMPARE(own.mesh->vertexCount(), written.size());
    const auto w = worldPositions(*own.mesh);
    double worstOwn = 0.0;
    for (size_t i = 0; i < written.size(); ++i) worstOwn = std::max(worstOwn, glm::length(w[i] - written[i]));
    // Millimetre differences survive exactly (to well below a micrometre).
    for (size_t i = 1; i <= 4; ++i) {
      const glm::dvec3 d = w[i] - w[0], e = written[i] - written[0];
      for (int k = 0; k < 3; ++k) QVERIFY2(std::abs(d[k] - e[k]) < 1e-6, qPrintable(QString("vertex %1 axis %2").arg(i).arg(k)));
    }
    QVERIFY(worstOwn < 1e-6);
    // The origin is double and the float offsets are small.
    QVERIFY(std::abs(own.mesh->origin.y - 5514553.0) < 20.0);
    for (const auto& q : own.mesh->positions) QVERIFY(glm::length(q) < 20.0f);

    // Assimp reads floats: 32 bits resolve only 0.5 m at a northing of 5.5e6 m.
    const ImportResult ai = importMesh(p, withReader(Reader::Assimp, UpAxis::Z));
    double worstAi = INFINITY;
    if (ai.ok()) {
      const auto wa = worldPositions(*ai.mesh);
      worstAi = maxNearestDistance(written, wa, 1.0);
    }
    qInfo("UTM test: largest position error own reader %.3g m, Assimp %.3g m (%s)", worstOwn, worstAi,
          ai.ok() ? "imported" : ai.error.c_str());
    QVERIFY2(worstAi > 0.01, "Assimp was expected to lose millimetre detail at UTM northings");
    // ...and its report says so, naming the file and the spacing of floats there.
    QVERIFY(ai.ok());
    QVERIFY2(anyWarningContains(ai.report, p, "32-bit float"), joinWarnings(ai.report).c_str());
    QVERIFY2(!anyWarningContains(own.report, "32-bit float"), joinWarnings(own.report).c_str());
  }

  // ---- bad input --------------------------------------------------------------

  void truncatedObj() {
    // The bunny cut in the middle of a line: a few characters into a line
    // half-way through the file.
    const std::string text = readFile(kBunny);
    const size_t lineStart = text.find('\n', text.size() / 2) + 1;
    QVERIFY(text.compare(lineStart, 2, "v ") == 0 || text.compare(lineStart, 2, "f ") == 0);
    const std::string p = path("bunny_truncated.obj");
    writeFile(p, text.substr(0, lineStart + 5));
    const size_t lineNo = size_t(std::count(text.begin(), text.begin() + long(lineStart), '\n')) + 1;
    for (Reader reader : {Reader::Auto, Reader::Obj}) {
      const ImportResult r = importMesh(p, withReader(reader));
      QVERIFY(!r.ok());
      QVERIFY(!r.cancelled);
      const std::string where = p + ":" + std::to_string(lineNo) + ":";
      QVERIFY2(r.error.find(where) != std::string::npos, r.error.c_str());
      QVERIFY2(r.error.find("truncated") != std::string::npos, r.error.c_str());
    }
  }

  void nanCoordinates() {
    const std::string p = path("nan.obj");
    // Two good triangles and two that use a NaN or an infinite vertex.
    writeFile(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 1 1 0\nv 0 inf 0\n"
                 "f 1 2 3\nf 1 2 4\nf 2 5 3\nf 3 5 6\n");
    const ImportResult r = importMesh(p);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(2));
    QCOMPARE(r.report.nonFiniteVertices, size_t(2));
    QCOMPARE(r.report.trianglesIn, size_t(4));
    QCOMPARE(r.report.trianglesOut, size_t(2));
    QVERIFY2(anyWarningContains(r.report, p, "NaN"), joinWarnings(r.report).c_str());
    QVERIFY2(anyWarningContains(r.report, "2 faces"), joinWarnings(r.report).c_str());
    for (const auto& q : r.mesh->positions) QVERIFY(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
  }

  void indicesOutOfRange() {
    const std::string p = path("range.obj");
    writeFile(p, "# out of range faces on lines 6 and 8\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\nf -1 -2 -3\nf 1 -7 2\n");
    const ImportResult r = importMesh(p);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(2));
    QCOMPARE(r.report.outOfRangeFaces, size_t(2));
    QVERIFY2(anyWarningContains(r.report, p + ":6:", "out of range"), joinWarnings(r.report).c_str());
  }

  void missingTexture() {
    const std::string dir = path("missing_tex");
    fs::create_directories(dir);
    expectTextureProblem(dir, "Stone", "stone_albedo.png", "not found");
  }

  void textureThatFailsToDecode() {
    const std::string dir = path("bad_tex");
    fs::create_directories(dir);
    // PNG signature, then garbage.
    std::string png("\x89PNG\r\n\x1a\n", 8);
    std::mt19937 rng(7);
    for (int i = 0; i < 200; ++i) png += char(rng() & 0xff);
    writeFile(dir + "/broken.png", png);
    expectTextureProblem(dir, "Bark", "broken.png", "Bark");
  }

  // A texture with a fifth channel (a TIFF with R, G, B, A and one more) is drawn
  // from its first four; both readers say so in the report, and the pixels
  // are the file's first four channels. (Textures of 1 to 4 channels say
  // nothing: objMtlPng, glbWithEmbeddedTexture and fbxWithTexture expect no
  // warning at all.)
  void textureWithMoreThanFourChannelsSaysSo() {
    const std::string dir = path("five_channels");
    fs::create_directories(dir);
    constexpr int w = 2, h = 2, nch = 5;
    std::vector<uint8_t> pixels(size_t(w) * h * nch);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(10 * (i / nch) + i % nch + 1);
    hs::image_io::Spec spec = hs::image_io::Spec::of(w, h, nch, hs::image_io::PixelType::UInt8);
    spec.channelNames = {"R", "G", "B", "A", "Z"};
    std::string error;
    QVERIFY2(hs::image_io::writeFile(dir + "/five.tif", spec, hs::image_io::PixelType::UInt8, pixels.data(), error),
             error.c_str());
    writeFile(dir + "/m.mtl", "newmtl Scan\nKd 1 1 1\nmap_Kd five.tif\n");
    writeFile(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl Scan\n"
                              "f 1/1 2/2 3/3\n");
    for (const Reader reader : {Reader::Obj, Reader::Assimp}) {
      ImportOptions options;
      options.reader = reader;
      const ImportResult r = importMesh(dir + "/m.obj", options);
      QVERIFY2(r.ok(), r.error.c_str());
      // (TIFF keeps no name for the fifth channel: OpenImageIO calls it "channel4".)
      QVERIFY2(anyWarningContains(r.report, "five.tif: 5 channels (R, G, B, A, ", "; drawn from the first 4, the others"),
               joinWarnings(r.report).c_str());
      QCOMPARE(r.mesh->textures.size(), size_t(1));
      const Texture& t = r.mesh->textures.front();
      QCOMPARE(t.width, w);
      for (size_t p = 0; p < size_t(w) * h; ++p)
        for (size_t c = 0; c < 4; ++c) QCOMPARE(t.rgba[p * 4 + c], pixels[p * nch + c]);
    }
  }

  void emptyFile() {
    const std::string p = path("empty.obj");
    writeFile(p, "");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("empty") != std::string::npos, r.error.c_str());
    // The in-memory entry point says the same.
    const ImportResult m = importObjFromMemory({}, "mem.obj", tmp_.path().toStdString());
    QVERIFY(!m.ok());
    QVERIFY2(m.error.find("mem.obj") != std::string::npos && m.error.find("empty") != std::string::npos, m.error.c_str());
  }

  void directoryInsteadOfFile() {
    const std::string p = path("folder.obj");
    fs::create_directories(p);
    for (Reader reader : {Reader::Auto, Reader::Assimp}) {
      const ImportResult r = importMesh(p, withReader(reader));
      QVERIFY(!r.ok());
      QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("directory") != std::string::npos, r.error.c_str());
    }
  }

  void missingFile() {
    const std::string p = path("no_such_file.obj");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("not found") != std::string::npos, r.error.c_str());
  }

  void binaryBytesNamedObj() {
    // A PNG renamed to .obj.
    const std::string p = path("picture.obj");
    writeFile(p, readFile(kData + "/checker_4x2.png"));
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("not a text OBJ") != std::string::npos, r.error.c_str());
  }

  void randomBytesNamedFbx() {
    const std::string p = path("random.fbx");
    std::mt19937 rng(1234);
    std::string bytes(4096, '\0');
    for (auto& c : bytes) c = char(rng() & 0xff);
    writeFile(p, bytes);
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY(!r.cancelled);
    QVERIFY2(r.error.rfind(p + ": ", 0) == 0, r.error.c_str());
    QVERIFY(r.error.size() > p.size() + 4);  // says why after the name
  }

  void unknownExtension() {
    const std::string p = path("notes.txt");
    writeFile(p, "v 0 0 0\n");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("'.txt'") != std::string::npos, r.error.c_str());
  }

  void meshWithNoFaces() {
    const std::string p = path("points.obj");
    writeFile(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("no faces") != std::string::npos, r.error.c_str());
    QCOMPARE(r.report.skippedLines, size_t(1));
  }

  void allDegenerateFaces() {
    const std::string p = path("degenerate.obj");
    writeFile(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 2 3 3\nf 3 1 3\n");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("nothing to import") != std::string::npos, r.error.c_str());
    QCOMPARE(r.report.degenerateFaces, size_t(3));
    // One good face among them is kept, the others counted.
    const std::string q = path("some_degenerate.obj");
    writeFile(q, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 1 2 3\nf 3 1 3\n");
    const ImportResult s = importMesh(q);
    QVERIFY2(s.ok(), s.error.c_str());
    QCOMPARE(s.mesh->triangleCount(), size_t(1));
    QCOMPARE(s.report.degenerateFaces, size_t(2));
    QVERIFY2(anyWarningContains(s.report, q, "2 faces repeat a vertex"), joinWarnings(s.report).c_str());
  }

  void malformedStatementNamesTheLine() {
    const std::string p = path("malformed.obj");
    writeFile(p, "v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    const ImportResult r = importMesh(p);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find(p + ":3:") != std::string::npos, r.error.c_str());
    QVERIFY2(r.error.find("truncated") == std::string::npos, r.error.c_str());  // the file ends cleanly
  }

  // ---- textures and formats ------------------------------------------------------

  void objMtlPng() {
    const ImportResult r = importMesh(kData + "/textured_quad.obj");
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY2(r.report.warnings.empty(), joinWarnings(r.report).c_str());
    QCOMPARE(r.report.polygonsTriangulated, size_t(1));
    // MTL's Kd is taken as linear RGB as written (Blender's convention).
    const glm::vec4 expected(0.25f, 0.5f, 0.75f, 1.0f);
    checkTexturedQuad(*r.mesh, expected);
    // Assimp's OBJ reader gives the same colour: the reader does not change it.
    ImportOptions viaAssimp;
    viaAssimp.reader = Reader::Assimp;
    const ImportResult assimp = importMesh(kData + "/textured_quad.obj", viaAssimp);
    QVERIFY2(assimp.ok(), assimp.error.c_str());
    checkTexturedQuad(*assimp.mesh, expected);
    QCOMPARE(r.mesh->materials.front().name, std::string(fx::kMaterialName));
    QCOMPARE(r.mesh->textures.front().name, std::string("checker_4x2.png"));
    // The kept bytes are the PNG file's.
    const std::string png = readFile(kData + "/checker_4x2.png");
    QCOMPARE(r.mesh->textures.front().encoded.size(), png.size());
    QVERIFY(std::equal(png.begin(), png.end(), r.mesh->textures.front().encoded.begin(),
                       [](char a, uint8_t b) { return uint8_t(a) == b; }));
  }

  void glbWithEmbeddedTexture() {
    const ImportResult r = importMesh(kData + "/textured_quad.glb");
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.reader, std::string("assimp"));
    QVERIFY(r.report.upAxisConverted);  // glTF is Y-up by specification
    checkTexturedQuad(*r.mesh, glm::vec4(fx::kBaseColor[0], fx::kBaseColor[1], fx::kBaseColor[2], fx::kBaseColor[3]));
    QVERIFY2(r.report.warnings.empty(), joinWarnings(r.report).c_str());
  }

  void fbxWithTexture() {
    const ImportResult r = importMesh(kData + "/textured_quad.fbx");
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.reader, std::string("assimp"));
    // The file declares Y up (UpAxis 1) and centimetres (UnitScaleFactor 1);
    // the importer converts to Z-up metres.
    const std::string text = readFile(kData + "/textured_quad.fbx");
    QVERIFY(text.find("\"UpAxis\", \"int\", \"Integer\", \"\", 1") != std::string::npos);
    QVERIFY(text.find("\"UnitScaleFactor\", \"double\", \"Number\", \"\", 1") != std::string::npos);
    QVERIFY(r.report.upAxisConverted);
    checkTexturedQuad(*r.mesh, glm::vec4(fx::kBaseColor[0], fx::kBaseColor[1], fx::kBaseColor[2], fx::kBaseColor[3]), 0.01);
    QVERIFY2(r.report.warnings.empty(), joinWarnings(r.report).c_str());
  }

  // PLY through our reader and through Assimp's (--reader assimp): the
  // same mesh either way.
  void ply_data() {
    QTest::addColumn<int>("reader");
    QTest::addColumn<QString>("name");
    QTest::newRow("own") << int(Reader::Auto) << "ply";
    QTest::newRow("assimp") << int(Reader::Assimp) << "assimp";
  }
  void ply() {
    QFETCH(int, reader);
    QFETCH(QString, name);
    ImportOptions o;
    o.reader = Reader(reader);
    const ImportResult r = importMesh(kData + "/quad_and_triangle.ply", o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.reader, name.toStdString());
    QCOMPARE(r.mesh->triangleCount(), size_t(3));  // the quad in two, and the triangle
    QVERIFY(r.report.upAxisConverted);
    QCOMPARE(r.mesh->uvs.size(), r.mesh->positions.size());
    // File (x, y, z, s, t) -> world (x, -z, y), uv (s, 1 - t).
    const float file[5][5] = {{0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {1, 1, 0, 1, 1}, {0, 1, 0, 0, 1}, {0.5f, 2, 0, 0.5f, 1}};
    const auto w = worldPositions(*r.mesh);
    for (const auto& f : file) {
      const glm::dvec3 expected(f[0], -f[2], f[1]);
      const size_t v = vertexNear(*r.mesh, expected);
      QVERIFY(glm::length(w[v] - expected) < 1e-6);
      QVERIFY(glm::length(r.mesh->uvs[v] - glm::vec2(f[3], 1.0f - f[4])) < 1e-6f);
    }
    QVERIFY(std::abs(surfaceArea(*r.mesh) - 1.5) < 1e-6);  // unit quad + triangle of base 1, height 1
  }

  // ---- progress and cancel -----------------------------------------------------------

  void progressIsReported() {
    const std::string p = path("grid.obj");
    writeFile(p, gridObj(300));  // 180,000 triangles, about 9 MB
    std::vector<double> fractions;
    hs::Progress progress([&](double f, std::string_view) { fractions.push_back(f); });
    const ImportResult r = importMesh(p, withReader(Reader::Obj, UpAxis::Z), &progress);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(2 * 300 * 300));
    QVERIFY(fractions.size() >= 3);
    QVERIFY(std::is_sorted(fractions.begin(), fractions.end()));
    QVERIFY(fractions.front() >= 0.0 && fractions.front() < 0.9);  // some while parsing
    QCOMPARE(fractions.back(), 1.0);
  }

  void cancelFromTheCallback_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("reader");
    QTest::addColumn<int>("cancelAtCall");
    QTest::newRow("large obj, first call") << "grid" << int(Reader::Obj) << 1;
    QTest::newRow("large obj, second call") << "grid" << int(Reader::Obj) << 2;
    QTest::newRow("bunny obj, first call") << "bunny" << int(Reader::Obj) << 1;
    QTest::newRow("bunny assimp, first call") << "bunny" << int(Reader::Assimp) << 1;
  }
  void cancelFromTheCallback() {
    QFETCH(QString, file);
    QFETCH(int, reader);
    QFETCH(int, cancelAtCall);
    const std::string p = file == "bunny" ? kBunny : path("grid.obj");
    if (file == "grid" && !fs::exists(p)) writeFile(p, gridObj(300));
    int calls = 0;
    double lastFraction = -1.0;
    hs::Progress* self = nullptr;
    hs::Progress progress([&](double f, std::string_view) {
      lastFraction = f;
      if (++calls == cancelAtCall) self->cancel();
    });
    self = &progress;
    const ImportResult r = importMesh(p, withReader(Reader(reader)), &progress);
    QVERIFY2(calls >= cancelAtCall, "the progress callback was never called");
    QVERIFY2(!r.ok(), "the import went on after Cancel");
    QVERIFY(r.cancelled);
    QVERIFY2(r.error.find(p) != std::string::npos && r.error.find("cancelled") != std::string::npos, r.error.c_str());
    QVERIFY(lastFraction < 1.0);  // it never reported completion
  }
};

QTEST_GUILESS_MAIN(TestMeshImport)
#include "test_mesh_import.moc"
