// The PLY reader (mesh/ply_reader.h) on files written here byte by byte:
// every format and layout it promises, against the numbers written, and
// every refusal naming the file, the element and the byte offset.
#include <QTemporaryDir>
#include <QtTest>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "mesh/mesh_export.h"
#include "mesh/mesh_import.h"

using namespace hs;
using namespace hs::mesh;

namespace {

// A small PLY writer for the fixtures: a header, then values in the
// chosen encoding.
struct PlyWriter {
  enum Enc { Ascii, Le, Be } enc;
  std::string header, body;
  explicit PlyWriter(Enc e) : enc(e) {
    header = std::string("ply\nformat ") + (e == Ascii ? "ascii" : e == Le ? "binary_little_endian" : "binary_big_endian") +
             " 1.0\n";
  }
  void line(const std::string& l) { header += l + "\n"; }
  template <class T>
  void put(T v) {
    if (enc == Ascii) {
      if constexpr (std::is_floating_point_v<T>) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g ", double(v));
        body += buf;
      } else {
        body += std::to_string(int64_t(v)) + " ";
      }
      return;
    }
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (enc == Be) std::reverse(b, b + sizeof(T));
    body.append(b, sizeof(T));
  }
  void endRow() {
    if (enc == Ascii) body += "\n";
  }
  std::string bytes() const { return header + "end_header\n" + body; }
};

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A 4 x 3 grid at UTM coordinates (doubles), with normals and s,t; faces:
// quads, except one row of triangles and one pentagon.
const glm::dvec3 kBase{500001.125, 4400002.375, 250.5};
constexpr int kNx = 4, kNy = 3;
glm::dvec3 gridPoint(int x, int y) { return kBase + glm::dvec3(1.5 * x, 2.0 * y, 0.25 * x * y); }

std::string gridPly(PlyWriter::Enc enc, bool colours = false) {
  PlyWriter w(enc);
  w.line("comment written by test_ply_reader");
  w.line("element vertex " + std::to_string(kNx * kNy));
  w.line("property double x");
  w.line("property double y");
  w.line("property double z");
  w.line("property float nx");
  w.line("property float ny");
  w.line("property float nz");
  w.line("property float s");
  w.line("property float t");
  if (colours) w.line("property uchar red\nproperty uchar green\nproperty uchar blue");
  w.line("element face 5");
  w.line("property list uchar int vertex_indices");
  w.line("element camera 1");  // an element nobody reads: skipped by size
  w.line("property float view_px");
  w.line("property float view_py");
  for (int y = 0; y < kNy; ++y)
    for (int x = 0; x < kNx; ++x) {
      const glm::dvec3 p = gridPoint(x, y);
      w.put(p.x);
      w.put(p.y);
      w.put(p.z);
      w.put(0.0f);
      w.put(0.0f);
      w.put(1.0f);
      w.put(float(x) / (kNx - 1));
      w.put(float(y) / (kNy - 1));
      if (colours) {
        w.put(uint8_t(200));
        w.put(uint8_t(100));
        w.put(uint8_t(50));
      }
      w.endRow();
    }
  auto idx = [](int x, int y) { return int32_t(y * kNx + x); };
  auto face = [&](std::initializer_list<int32_t> v) {
    w.put(uint8_t(v.size()));
    for (int32_t i : v) w.put(i);
    w.endRow();
  };
  face({idx(0, 0), idx(1, 0), idx(1, 1), idx(0, 1)});                          // quad: 2
  face({idx(1, 0), idx(2, 0), idx(2, 1)});                                      // triangle: 1
  face({idx(1, 0), idx(2, 1), idx(1, 1)});                                      // triangle: 1
  face({idx(2, 0), idx(3, 0), idx(3, 1), idx(3, 2), idx(2, 1)});                // pentagon: 3
  face({idx(0, 1), idx(1, 1), idx(1, 2), idx(0, 2)});                          // quad: 2
  w.put(1.0f);
  w.put(2.0f);
  w.endRow();
  return w.bytes();
}
constexpr size_t kGridTriangles = 9;

glm::dvec3 corner(const MeshData& m, size_t c) { return m.origin + glm::dvec3(m.positions[m.indices[c]]); }

}  // namespace

class TestPlyReader : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const std::string& name) const { return (std::filesystem::path(tmp_.path().toStdString()) / name).string(); }

  ImportResult importZUp(const std::string& p) {
    ImportOptions o;
    o.up = UpAxis::Z;
    o.recenter = false;
    return importMesh(p, o);
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  // LE, BE and ASCII: the same triangles at the same UTM positions (double
  // in the file, floats around a double origin here: within float
  // rounding of coordinates of a few metres), polygons fanned and counted,
  // the unknown element skipped, normals and UVs (t flipped to the mesh's
  // top-left convention) kept.
  void everyEncodingReadsTheSameMesh_data() {
    QTest::addColumn<int>("enc");
    QTest::newRow("binary little-endian") << int(PlyWriter::Le);
    QTest::newRow("binary big-endian") << int(PlyWriter::Be);
    QTest::newRow("ascii") << int(PlyWriter::Ascii);
  }
  void everyEncodingReadsTheSameMesh() {
    QFETCH(int, enc);
    const std::string f = path("grid.ply");
    writeFile(f, gridPly(PlyWriter::Enc(enc)));
    const ImportResult r = importZUp(f);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.reader, std::string("ply"));
    const MeshData& m = *r.mesh;
    QCOMPARE(m.triangleCount(), kGridTriangles);
    QCOMPARE(r.report.polygonsTriangulated, size_t(3));
    QCOMPARE(r.report.verticesIn, size_t(kNx * kNy));
    QVERIFY(!r.report.normalsGenerated);
    // The first corner of the first face is grid point (0,0).
    QVERIFY(glm::length(corner(m, 0) - gridPoint(0, 0)) < 1e-6);
    // Every corner: its UV (s,t were x,y over the grid, t flipped on
    // import) names the grid point it must sit at. (Unused vertices are
    // dropped on import, so indices are not the file's.)
    for (size_t c = 0; c < m.indices.size(); ++c) {
      const uint32_t v = m.indices[c];
      const int x = int(std::lround(m.uvs[v].x * (kNx - 1))), y = int(std::lround((1.0f - m.uvs[v].y) * (kNy - 1)));
      QVERIFY2(glm::length(corner(m, c) - gridPoint(x, y)) < 1e-6, qPrintable(QString::number(c)));
      QCOMPARE(m.normals[v], glm::vec3(0, 0, 1));
    }
    QVERIFY(r.report.warnings.empty());
  }

  // Binary face lists are read a 4 MB piece at a time on every thread
  // (mesh/ply_face_lists.h); ASCII face by face. A grid of quads, triangle
  // pairs and pentagons over 4 MB of faces (pieces end inside faces), with
  // faces of 2 corners and indices out of range (too large, negative) in
  // different pieces: every encoding gives the same mesh and counts, and
  // the binary files name the first three bad faces at their byte offsets.
  void binaryFacesOnAllThreadsMatchFaceByFace() {
    constexpr int n = 520;  // vertices per side
    std::vector<std::vector<int32_t>> faces;
    size_t triangles = 0, polygons = 0;
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
        if ((i + j) % 3 == 0) faces.push_back({a, b, d, c}), triangles += 2, ++polygons;
        else if ((i + j) % 3 == 1) faces.push_back({a, b, d}), faces.push_back({a, d, c}), triangles += 2;
        else if (i + 2 < n) faces.push_back({a, b, b + 1, d + 1, c}), triangles += 3, ++polygons, ++i;
        else faces.push_back({a, b, d}), triangles += 1;
      }
    const std::vector<std::pair<size_t, std::vector<int32_t>>> bad = {
        {10, {1, 2}}, {150000, {3, n * n, 4}}, {250000, {5, 6, -7, 8}}, {260000, {0, 1}}};
    QVERIFY(faces.size() > bad.back().first);
    for (const auto& [at, face] : bad) faces.insert(faces.begin() + ptrdiff_t(at), face);  // ends at index `at`
    std::vector<MeshData> meshes;
    std::vector<ImportReport> reports;
    for (PlyWriter::Enc enc : {PlyWriter::Ascii, PlyWriter::Le, PlyWriter::Be}) {
      PlyWriter w(enc);
      w.line("element vertex " + std::to_string(n * n));
      w.line("property float x\nproperty float y\nproperty float z");
      w.line("element face " + std::to_string(faces.size()));
      w.line("property list uchar int vertex_indices");
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          w.put(float(i));
          w.put(float(j));
          w.put(0.1f * float((i * 7 + j * 3) % 5));
          w.endRow();
        }
      std::vector<size_t> at;
      const size_t head = w.header.size() + std::strlen("end_header\n");
      for (size_t f = 0, k = 0; f < faces.size(); ++f) {
        if (k < bad.size() && bad[k].first == f) at.push_back(head + w.body.size()), ++k;
        w.put(uint8_t(faces[f].size()));
        for (int32_t v : faces[f]) w.put(v);
        w.endRow();
      }
      const std::string f = path("big_faces.ply");
      writeFile(f, w.bytes());
      if (enc != PlyWriter::Ascii) QVERIFY(w.body.size() - size_t(n * n * 12) > size_t(4) << 20);
      ImportResult r = importZUp(f);
      QVERIFY2(r.ok(), r.error.c_str());
      QCOMPARE(r.report.outOfRangeFaces, size_t(2));
      QCOMPARE(r.report.degenerateFaces, size_t(2));
      QCOMPARE(r.report.polygonsTriangulated, polygons);
      QCOMPARE(r.report.trianglesIn, triangles);
      QCOMPARE(r.report.declaredTriangles, triangles + 1 + 2);  // the bad faces of 3 and 4 corners declare 1 and 2
      QCOMPARE(r.mesh->triangleCount(), triangles);
      if (enc != PlyWriter::Ascii) {
        QVERIFY(r.report.warnings.size() >= 4);  // three faces named, then the sum
        QCOMPARE(r.report.warnings[3], f + ": 4 faces or strips dropped in all (vertex indices out of range, or "
                                           "fewer than 3 corners)");
        const std::string total = std::to_string(faces.size());
        QCOMPARE(r.report.warnings[0], f + ": face 11 of " + total + " (byte " + std::to_string(at[0]) +
                                           "): a face with 2 corners (dropped)");
        QCOMPARE(r.report.warnings[1], f + ": face 150001 of " + total + " (byte " + std::to_string(at[1]) +
                                           "): a vertex index outside 0.." + std::to_string(n * n) +
                                           " (the face is dropped)");
        QCOMPARE(r.report.warnings[2], f + ": face 250001 of " + total + " (byte " + std::to_string(at[2]) +
                                           "): a vertex index outside 0.." + std::to_string(n * n) +
                                           " (the face is dropped)");
      }
      meshes.push_back(std::move(*r.mesh));
      reports.push_back(r.report);
    }
    QCOMPARE(contentHash(meshes[1]), contentHash(meshes[0]));
    QCOMPARE(contentHash(meshes[2]), contentHash(meshes[0]));
    // The first triangles are the file's first faces, fanned.
    const MeshData& m = meshes[1];
    auto at = [&](size_t c) { return m.origin + glm::dvec3(m.positions[m.indices[c]]); };
    QCOMPARE(at(0).x - at(1).x, -1.0);  // a=(0,0), b=(1,0), d=(1,1) of the first quad
    QCOMPARE(at(2).y - at(0).y, 1.0);
  }

  // Y up unless told: (x, y, z) in the file is (x, -z, y) here.
  void yUpByDefault() {
    const std::string f = path("yup.ply");
    writeFile(f, gridPly(PlyWriter::Le));
    ImportOptions o;
    o.recenter = false;
    const ImportResult r = importMesh(f, o);
    QVERIFY2(r.ok(), r.error.c_str());
    const glm::dvec3 p = gridPoint(0, 0);
    QVERIFY(glm::length(corner(*r.mesh, 0) - glm::dvec3(p.x, -p.z, p.y)) < 1e-6);
    QVERIFY(r.report.upAxisConverted);
  }

  // Triangle strips with -1 restarts: the triangles of a 3 x 2 quad grid,
  // all facing +Z (alternating winding undone), none lost; Assimp read a
  // real tristrip scan as one triangle.
  void tristripsWithRestarts() {
    PlyWriter w(PlyWriter::Le);
    w.line("element vertex 12");
    w.line("property float x\nproperty float y\nproperty float z");
    w.line("element tristrips 1");
    w.line("property list int int vertex_indices");
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        w.put(float(x));
        w.put(float(y));
        w.put(0.0f);
      }
    // Row 0-1 as one strip, -1, row 1-2 as another: 6 triangles each.
    std::vector<int32_t> strip;
    for (int row = 0; row < 2; ++row) {
      if (row) strip.push_back(-1);
      for (int x = 0; x < 4; ++x) {
        strip.push_back((row + 1) * 4 + x);
        strip.push_back(row * 4 + x);
      }
    }
    w.put(int32_t(strip.size()));
    for (int32_t i : strip) w.put(i);
    writeFile(path("strips.ply"), w.bytes());
    const ImportResult r = importZUp(path("strips.ply"));
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(12));
    double area = 0.0;
    for (size_t t = 0; t < 12; ++t) {
      const glm::dvec3 n = glm::cross(corner(*r.mesh, 3 * t + 1) - corner(*r.mesh, 3 * t),
                                      corner(*r.mesh, 3 * t + 2) - corner(*r.mesh, 3 * t));
      QVERIFY2(n.z > 0.0, qPrintable(QString("triangle %1 faces down").arg(t)));
      area += 0.5 * n.z;
    }
    QCOMPARE(area, 6.0);  // the 3 x 2 metres the strips cover, no overlap
    QCOMPARE(r.report.declaredTriangles, size_t(12));
    QVERIFY(r.report.warnings.empty());
  }

  // MeshLab's per-face texcoord lists with texnumber over two TextureFile
  // textures: vertices split where corners disagree, one submesh per
  // texture, the textures loaded from beside the file.
  void perFaceTexcoordsAndTexnumber() {
    // Two 2 x 2 textures beside the file, written through our exporter's
    // PNG path (an independent check: OIIO reads them back).
    for (const char* name : {"a.png", "b.png"}) {
      MeshData tri;
      tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
      tri.uvs = {{0, 0}, {1, 0}, {0, 1}};
      tri.indices = {0, 1, 2};
      tri.submeshes = {{0, 3, 0}};
      Material mat;
      mat.diffuseTexture = 0;
      tri.materials = {mat};
      Texture t;
      t.name = name;
      t.width = t.height = 2;
      t.rgba.assign(16, name[0] == 'a' ? 40 : 220);
      tri.textures = {t};
      ExportOptions o;
      o.format = ExportFormat::Ply;
      QVERIFY(exportMesh(tri, path(std::string("tex_") + name[0] + ".ply"), o).ok());
      std::filesystem::rename(path(std::string("tex_") + name[0] + ".png"), path(name));
    }
    PlyWriter w(PlyWriter::Ascii);
    w.line("comment TextureFile a.png");
    w.line("comment TextureFile b.png");
    w.line("element vertex 4");
    w.line("property float x\nproperty float y\nproperty float z");
    w.line("element face 2");
    w.line("property list uchar int vertex_indices");
    w.line("property list uchar float texcoord");
    w.line("property int texnumber");
    for (glm::vec3 v : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}) {
      w.put(v.x);
      w.put(v.y);
      w.put(v.z);
      w.endRow();
    }
    // Two triangles sharing the edge 0-2, with different UVs there (a seam).
    w.put(uint8_t(3)); w.put(0); w.put(1); w.put(2);
    w.put(uint8_t(6)); w.put(0.0f); w.put(0.0f); w.put(1.0f); w.put(0.0f); w.put(1.0f); w.put(1.0f);
    w.put(0); w.endRow();
    w.put(uint8_t(3)); w.put(0); w.put(2); w.put(3);
    w.put(uint8_t(6)); w.put(0.5f); w.put(0.5f); w.put(0.75f); w.put(0.75f); w.put(0.5f); w.put(0.75f);
    w.put(1); w.endRow();
    writeFile(path("faceuv.ply"), w.bytes());
    const ImportResult r = importZUp(path("faceuv.ply"));
    QVERIFY2(r.ok(), r.error.c_str());
    const MeshData& m = *r.mesh;
    QCOMPARE(m.triangleCount(), size_t(2));
    QCOMPARE(m.vertexCount(), size_t(6));  // corners 0 and 2 split: their UVs differ per face
    QCOMPARE(m.textures.size(), size_t(2));
    QCOMPARE(m.submeshes.size(), size_t(2));
    QCOMPARE(m.materials[size_t(m.submeshes[1].material)].diffuseTexture, 1);
    QCOMPARE(int(m.textures[1].rgba[0]), 220);
    // The second face's first corner: texcoord (0.5, 0.5), v flipped.
    QCOMPARE(m.uvs[m.indices[m.submeshes[1].firstIndex]], glm::vec2(0.5f, 0.5f));
    QCOMPARE(m.uvs[m.indices[1]], glm::vec2(1.0f, 1.0f));
  }

  // Vertex colours are read and not kept: said in a warning.
  void coloursAreNamedAsNotImported() {
    writeFile(path("colours.ply"), gridPly(PlyWriter::Le, true));
    const ImportResult r = importZUp(path("colours.ply"));
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), kGridTriangles);  // the colours did not shift what follows
    QCOMPARE(r.report.warnings.size(), size_t(1));
    QVERIFY(r.report.warnings[0].find("colours") != std::string::npos);
  }

  // Our exporter's OBJ and PLY of one mesh read back identically.
  void sameMeshAsObjAndPly() {
    writeFile(path("src.ply"), gridPly(PlyWriter::Le));
    const ImportResult src = importZUp(path("src.ply"));
    QVERIFY(src.ok());
    for (ExportFormat f : {ExportFormat::Obj, ExportFormat::Ply}) {
      ExportOptions o;
      o.format = f;
      o.world = true;
      o.zUp = true;
      QVERIFY(exportMesh(*src.mesh, path(f == ExportFormat::Obj ? "same.obj" : "same.ply"), o).ok());
    }
    const ImportResult obj = importZUp(path("same.obj")), ply = importZUp(path("same.ply"));
    QVERIFY2(obj.ok() && ply.ok(), (obj.error + ply.error).c_str());
    // Corner by corner (the OBJ reader orders vertices by first use).
    QCOMPARE(ply.mesh->origin, obj.mesh->origin);
    QCOMPARE(ply.mesh->indices.size(), obj.mesh->indices.size());
    for (size_t c = 0; c < ply.mesh->indices.size(); ++c) {
      QCOMPARE(ply.mesh->positions[ply.mesh->indices[c]], obj.mesh->positions[obj.mesh->indices[c]]);
      QCOMPARE(ply.mesh->uvs[ply.mesh->indices[c]], obj.mesh->uvs[obj.mesh->indices[c]]);
    }
  }

  // Refusals: one message naming the file and the place; nothing imported.
  void badFilesAreRefusedWithTheirPlace_data() {
    QTest::addColumn<QByteArray>("bytes");
    QTest::addColumn<QStringList>("expected");
    const std::string grid = gridPly(PlyWriter::Le);
    const std::string tri = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    QTest::newRow("count beyond 64 bits")
        << QByteArray((tri + "element face 99999999999999999999\nproperty list uchar int vertex_indices\nend_header\n")
                          .c_str())
        << QStringList{":7:", "99999999999999999999", "too large"};
    QTest::newRow("count as a float")
        << QByteArray((tri + "element face 1e9\nproperty list uchar int vertex_indices\nend_header\n").c_str())
        << QStringList{":7:", "1e9", "not a whole number"};
    QTest::newRow("count beyond the file")
        << QByteArray("ply\nformat binary_little_endian 1.0\nelement vertex 99999999\nproperty float x\nend_header\n"
                      "abcd")
        << QStringList{":3:", "element vertex declares 99999999 rows", "only 4 bytes"};
    QTest::newRow("no end_header") << QByteArray("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n")
                                   << QStringList{"end_header"};
    QTest::newRow("unknown type")
        << QByteArray("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n1\n")
        << QStringList{":4:", "float128"};
    QTest::newRow("binary body cut short") << QByteArray(grid.substr(0, grid.size() - 40).c_str(), qsizetype(grid.size() - 40))
                                           << QStringList{"byte", "cut short"};
    QTest::newRow("ascii body cut short")
        << QByteArray((tri + "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1")
                          .c_str())
        << QStringList{"in face 1 of 1", "byte", "cut short"};
    QTest::newRow("list longer than the file")
        << QByteArray((tri + "element face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                             "4000000000 0 1 2\n")
                          .c_str())
        << QStringList{"in face 1 of 1", "4000000000", "past the end"};
    QTest::newRow("not a number")
        << QByteArray((tri + "end_header\n0 0 0\n1 zero 0\n0 1 0\n").c_str()) << QStringList{"in vertex 2 of 3", "'zero'"};
  }
  void badFilesAreRefusedWithTheirPlace() {
    QFETCH(QByteArray, bytes);
    QFETCH(QStringList, expected);
    const std::string f = path("bad.ply");
    writeFile(f, bytes.toStdString());
    const ImportResult r = importZUp(f);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("bad.ply") != std::string::npos, r.error.c_str());
    for (const QString& e : expected) QVERIFY2(r.error.find(e.toStdString()) != std::string::npos, r.error.c_str());
  }

  // A truncated strip list and an index out of range: the truncation is an
  // error; the bad index drops its face, counted and named.
  void truncatedStripAndBadIndex() {
    PlyWriter w(PlyWriter::Le);
    w.line("element vertex 4");
    w.line("property float x\nproperty float y\nproperty float z");
    w.line("element tristrips 1");
    w.line("property list int int vertex_indices");
    for (int i = 0; i < 4; ++i) {
      w.put(float(i % 2));
      w.put(float(i / 2));
      w.put(0.0f);
    }
    w.put(int32_t(6));
    for (int32_t i : {0, 1, 2, 3}) w.put(i);  // two of six entries missing
    writeFile(path("cutstrip.ply"), w.bytes());
    ImportResult r = importZUp(path("cutstrip.ply"));
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("tristrips 1 of 1") != std::string::npos && r.error.find("cut short") != std::string::npos,
             r.error.c_str());

    PlyWriter g(PlyWriter::Ascii);
    g.line("element vertex 3\nproperty float x\nproperty float y\nproperty float z");
    g.line("element face 2\nproperty list uchar int vertex_indices");
    g.body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 7\n";
    writeFile(path("badindex.ply"), g.bytes());
    r = importZUp(path("badindex.ply"));
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.mesh->triangleCount(), size_t(1));
    QCOMPARE(r.report.outOfRangeFaces, size_t(1));
    QCOMPARE(r.report.declaredTriangles, size_t(2));  // declared two, kept one: the report says both
    QCOMPARE(r.report.trianglesOut, size_t(1));
    QVERIFY(!r.report.warnings.empty() && r.report.warnings[0].find("face 2 of 2") != std::string::npos);
    QVERIFY(r.report.warnings.back().find("declares 2 triangles") != std::string::npos);
    // --strict refuses it.
    ImportOptions strict;
    strict.up = UpAxis::Z;
    strict.strict = true;
    const ImportResult refused = importMesh(path("badindex.ply"), strict);
    QVERIFY(!refused.ok());
    QVERIFY2(refused.error.find("--strict") != std::string::npos, refused.error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestPlyReader)
#include "test_ply_reader.moc"
