// Mesh export (mesh/mesh_export.h): each format read back by an importer
// (our OBJ reader; Assimp for PLY and GLB, an independent implementation)
// or by parsing the file's bytes here, against the mesh that was written.
#include <QTemporaryDir>
#include <QtTest>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/json.h"
#include "mesh/mesh_export.h"
#include "mesh/mesh_import.h"

using namespace hs;
using namespace hs::mesh;
namespace fs = std::filesystem;

namespace {

// A georeferenced scan-like patch: a wavy 12 x 9 grid at UTM coordinates,
// with UVs, normals, two materials (one textured with a 4 x 4 texture).
MeshData scanPatch() {
  MeshData m;
  m.origin = {500123.25, 4400456.5, 312.75};
  const int nx = 12, ny = 9;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      m.positions.emplace_back(0.37f * float(x) - 2.0f, 0.41f * float(y) - 1.5f,
                               0.2f * std::sin(float(x) * 0.9f) * std::cos(float(y) * 0.7f));
      m.uvs.emplace_back(float(x) / float(nx - 1), float(y) / float(ny - 1));
    }
  for (int y = 0; y + 1 < ny; ++y)
    for (int x = 0; x + 1 < nx; ++x) {
      const uint32_t i = uint32_t(y * nx + x);
      m.indices.insert(m.indices.end(), {i, i + 1, i + nx, i + 1, i + nx + 1, i + nx});
    }
  computeVertexNormals(m);
  const uint32_t half = uint32_t(m.indices.size() / 6 * 3);
  m.submeshes = {{0, half, 0}, {half, uint32_t(m.indices.size()) - half, 1}};
  Material rock;
  rock.name = "rock";
  rock.baseColor = {0.5f, 0.4f, 0.3f, 1.0f};
  rock.diffuseTexture = 0;
  Material moss;
  moss.name = "moss";
  moss.baseColor = {0.1f, 0.6f, 0.2f, 1.0f};
  m.materials = {rock, moss};
  Texture t;
  t.name = "rock.png";
  t.width = t.height = 4;
  for (int i = 0; i < 16; ++i)
    // Alpha below 1 on most texels: the texels must come back as they are
    // (straight colour), not with the alpha multiplied in or divided out.
    t.rgba.insert(t.rgba.end(), {uint8_t(i * 16), uint8_t(255 - i * 16), uint8_t(i * 7), uint8_t(255 - i * 15)});
  m.textures = {t};
  return m;
}

glm::dvec3 worldCorner(const MeshData& m, size_t corner) {
  return m.origin + glm::dvec3(m.positions[m.indices[corner]]);
}

// Every triangle's corners at the same world places, in order.
bool sameTriangles(const MeshData& a, const MeshData& b, double tolerance, QByteArray& why) {
  if (a.triangleCount() != b.triangleCount()) {
    why = "triangles: " + QByteArray::number(qulonglong(a.triangleCount())) + " vs " +
          QByteArray::number(qulonglong(b.triangleCount()));
    return false;
  }
  double worst = 0.0;
  for (size_t c = 0; c < a.indices.size(); ++c)
    worst = std::max(worst, glm::length(worldCorner(a, c) - worldCorner(b, c)));
  why = "largest corner distance " + QByteArray::number(worst, 'g', 3) + " m";
  return worst <= tolerance;
}

bool sameUvs(const MeshData& a, const MeshData& b, float tolerance) {
  if (a.uvs.empty() || b.uvs.empty()) return false;
  for (size_t c = 0; c < a.indices.size(); ++c)
    if (glm::length(a.uvs[a.indices[c]] - b.uvs[b.indices[c]]) > tolerance) return false;
  return true;
}

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

class TestMeshExport : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const char* name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  // Relative positions + the offset sidecar, read back by our OBJ reader
  // with --origin auto: the same world positions to float precision (two
  // roundings of ~3 m coordinates), the same UVs, materials and texels.
  void objRoundTrip() {
    const MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Obj;
    const ExportResult r = exportMesh(m, path("patch.obj"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.written.front(), path("patch.obj"));
    QVERIFY(fs::exists(path("patch.mtl")) && fs::exists(path("patch_offset.xyz")) && fs::exists(path("patch_0.png")));
    ImportOptions io;
    io.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    const ImportResult back = importMesh(path("patch.obj"), io);
    QVERIFY2(back.ok(), back.error.c_str());
    QByteArray why;
    QVERIFY2(sameTriangles(m, *back.mesh, 1e-6, why), why);
    QVERIFY(sameUvs(m, *back.mesh, 1e-7f));
    QCOMPARE(back.mesh->materials.size(), size_t(2));
    QCOMPARE(back.mesh->submeshes.size(), size_t(2));
    QCOMPARE(back.mesh->materials[0].baseColor, m.materials[0].baseColor);  // Kd is linear both ways
    QCOMPARE(back.mesh->textures.size(), size_t(1));
    QCOMPARE(back.mesh->textures[0].rgba, m.textures[0].rgba);
  }

  // World coordinates in OBJ keep every digit: positions read back exactly
  // as the doubles written (our OBJ reader parses doubles).
  void objWorldKeepsEveryDigit() {
    const MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Obj;
    o.world = true;
    o.zUp = true;
    const ExportResult r = exportMesh(m, path("world.obj"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(!fs::exists(path("world_offset.xyz")));
    std::istringstream in(readAll(path("world.obj")));
    std::string line;
    size_t v = 0;
    while (std::getline(in, line))
      if (line.rfind("v ", 0) == 0) {
        std::istringstream ls(line.substr(2));
        glm::dvec3 p;
        ls >> p.x >> p.y >> p.z;
        QCOMPARE(p, m.origin + glm::dvec3(m.positions[v]));
        ++v;
      }
    QCOMPARE(v, m.positions.size());
  }

  // Binary PLY read by Assimp (not our code): same triangles and UVs.
  void plyRoundTripThroughAssimp() {
    const MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Ply;
    o.zUp = true;
    const ExportResult r = exportMesh(m, path("patch.ply"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    ImportOptions io;
    io.up = UpAxis::Z;
    io.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    io.reader = Reader::Assimp;  // not our PLY reader: an independent one
    const ImportResult back = importMesh(path("patch.ply"), io);
    QVERIFY2(back.ok(), back.error.c_str());
    QByteArray why;
    QVERIFY2(sameTriangles(m, *back.mesh, 1e-6, why), why);
    QVERIFY(sameUvs(m, *back.mesh, 1e-7f));
  }

  // --world PLY: doubles, read here from the bytes: exactly origin + p.
  void plyWorldHoldsDoubles() {
    const MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Ply;
    o.world = true;
    o.zUp = true;
    QVERIFY(exportMesh(m, path("world.ply"), o).ok());
    const std::string bytes = readAll(path("world.ply"));
    const size_t body = bytes.find("end_header\n");
    QVERIFY(body != std::string::npos);
    const std::string header = bytes.substr(0, body);
    QVERIFY(header.find("property double x") != std::string::npos);
    QVERIFY(header.find("element face " + std::to_string(m.triangleCount())) != std::string::npos);
    const size_t stride = 24 + 12 + 8;  // xyz double, normal float, st float
    const char* p = bytes.data() + body + 11;
    for (size_t i = 0; i < m.positions.size(); ++i) {
      double xyz[3];
      std::memcpy(xyz, p + i * stride, 24);
      const glm::dvec3 want = m.origin + glm::dvec3(m.positions[i]);
      QCOMPARE(glm::dvec3(xyz[0], xyz[1], xyz[2]), want);
    }
    // Faces: 3 then three int indices, as in the mesh.
    const char* f = p + m.positions.size() * stride;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      QCOMPARE(uint8_t(f[t * 13]), uint8_t(3));
      int32_t idx[3];
      std::memcpy(idx, f + t * 13 + 1, 12);
      for (int k = 0; k < 3; ++k) QCOMPARE(uint32_t(idx[k]), m.indices[t * 3 + size_t(k)]);
    }
    QCOMPARE(size_t(f + m.triangleCount() * 13 - bytes.data()), bytes.size());
  }

  // GLB read by Assimp: same triangles (relative to the node: no world
  // translation without --world, the origin in the sidecar) and UVs (MeshData and glTF share a convention,
  // kept by the importer); --world puts the origin, Y-up, in the node's
  // translation as JSON doubles.
  void glbRoundTripThroughAssimp() {
    MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Glb;
    QVERIFY(exportMesh(m, path("patch.glb"), o).ok());
    const ImportResult back = importMesh(path("patch.glb"));
    QVERIFY2(back.ok(), back.error.c_str());
    MeshData local = m;
    local.origin = glm::dvec3(0.0);
    QByteArray why;
    QVERIFY2(sameTriangles(local, *back.mesh, 1e-6, why), why);
    // The origin is in the sidecar, as for OBJ and PLY: --origin auto puts
    // the mesh back where it was.
    ImportOptions io;
    io.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    QVERIFY(exportMesh(m, path("alone.glb"), o).ok());  // a stem no other test writes
    QVERIFY(fs::exists(path("alone_offset.xyz")));
    const ImportResult placed = importMesh(path("alone.glb"), io);
    QVERIFY2(placed.ok(), placed.error.c_str());
    QVERIFY2(sameTriangles(m, *placed.mesh, 1e-6, why), why);
    QVERIFY(sameUvs(m, *back.mesh, 1e-6f));
    // Both materials with their colours (Assimp adds a default one of its own).
    for (const Material& want : m.materials) {
      bool found = false;
      for (const Material& got : back.mesh->materials)
        found |= got.name == want.name && glm::length(got.baseColor - want.baseColor) < 1e-6f;
      QVERIFY2(found, want.name.c_str());
    }
    // The texture travels inside the file, texel for texel.
    QCOMPARE(back.mesh->textures.size(), size_t(1));
    QCOMPARE(back.mesh->textures[0].rgba, m.textures[0].rgba);

    o.world = true;
    QVERIFY(exportMesh(m, path("world.glb"), o).ok());
    const std::string bytes = readAll(path("world.glb"));
    uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    std::string error;
    const std::optional<Json> j = parseJson(bytes.substr(20, jsonLength), error);
    QVERIFY2(j, error.c_str());
    const Json& t = (*j)["nodes"][0]["translation"];
    QCOMPARE(t[0].get<double>(), m.origin.x);
    QCOMPARE(t[1].get<double>(), m.origin.z);
    QCOMPARE(t[2].get<double>(), -m.origin.y);
  }

  // An instance's transform: positions placed in double; a mirroring
  // transform reverses the winding so faces still face their normals.
  void placedAndMirrored() {
    const MeshData m = scanPatch();
    ExportOptions o;
    o.format = ExportFormat::Obj;
    o.zUp = true;
    o.world = true;
    o.transform = glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(10.0, -20.0, 5.0)), glm::dvec3(-2.0, 2.0, 2.0));
    QVERIFY(exportMesh(m, path("mirror.obj"), o).ok());
    ImportOptions io;
    io.up = UpAxis::Z;
    const ImportResult back = importMesh(path("mirror.obj"), io);
    QVERIFY2(back.ok(), back.error.c_str());
    const MeshData& b = *back.mesh;
    QCOMPARE(b.triangleCount(), m.triangleCount());
    for (size_t t = 0; t < b.triangleCount(); ++t) {
      const glm::dvec3 a = b.origin + glm::dvec3(b.positions[b.indices[t * 3]]);
      const glm::dvec3 c1 = b.origin + glm::dvec3(b.positions[b.indices[t * 3 + 1]]);
      const glm::dvec3 c2 = b.origin + glm::dvec3(b.positions[b.indices[t * 3 + 2]]);
      const glm::dvec3 faceNormal = glm::cross(c1 - a, c2 - a);
      QVERIFY(glm::dot(faceNormal, glm::dvec3(b.normals[b.indices[t * 3]])) > 0.0);
      // Corner 0 stays corner 0: it is placed where the transform puts it.
      const glm::dvec3 want = glm::dvec3(o.transform * glm::dvec4(worldCorner(m, t * 3), 1.0));
      QVERIFY(glm::length(a - want) < 1e-6);
    }
  }

  // Bad requests: an error naming the file, nothing written.
  // A mesh at the origin written over an earlier export of a georeferenced
  // one: the sidecar the first left would put the second 5,000 km away on
  // an import that reads sidecars. It is overwritten with a zero offset
  // (and so for a world export); GLB reads none of it. Found by
  // meshproc_defect_campaign --export.
  void aStaleOffsetSidecarIsOverwritten() {
    const MeshData geo = scanPatch();
    MeshData local = geo;
    local.origin = glm::dvec3(0.0);
    for (const bool world : {false, true})
      for (const ExportFormat f : {ExportFormat::Obj, ExportFormat::Ply}) {
        const std::string file = path(f == ExportFormat::Obj ? "stale.obj" : "stale.ply");
        ExportOptions o;
        o.format = f;
        o.zUp = true;
        QVERIFY(exportMesh(geo, file, o).ok());
        QVERIFY(fs::exists(path("stale_offset.xyz")));
        o.world = world;
        const MeshData& second = world ? geo : local;
        const ExportResult r = exportMesh(second, file, o);
        QVERIFY2(r.ok(), r.error.c_str());
        ImportOptions io;
        io.up = UpAxis::Z;
        io.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
        const ImportResult back = importMesh(file, io);
        QVERIFY2(back.ok(), back.error.c_str());
        QByteArray why;
        QVERIFY2(sameTriangles(second, *back.mesh, 1e-6, why), why + (world ? " (world)" : ""));
        QCOMPARE(readAll(path("stale_offset.xyz")), std::string("0 0 0\n"));
        fs::remove(path("stale_offset.xyz"));
      }
    // No sidecar beside it, none needed: none written.
    ExportOptions o;
    o.format = ExportFormat::Obj;
    const ExportResult r = exportMesh(local, path("plain.obj"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(!fs::exists(path("plain_offset.xyz")));
  }

  // PLY holds no materials and one texture: a mesh with more says so in
  // the result's warnings (which the CLI and the editor show), naming the
  // file; OBJ and GLB keep them and say nothing.
  void whatPlyCannotHoldIsSaid() {
    const MeshData m = scanPatch();  // two materials with faces, one texture
    ExportOptions o;
    o.format = ExportFormat::Ply;
    const ExportResult r = exportMesh(m, path("two.ply"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.warnings.size(), size_t(1));
    QVERIFY2(r.warnings[0].find(path("two.ply")) == 0 && r.warnings[0].find("2 materials") != std::string::npos &&
                 r.warnings[0].find("textures") == std::string::npos,
             r.warnings[0].c_str());
    MeshData two = m;
    two.textures.push_back(two.textures[0]);
    two.materials[1].diffuseTexture = 1;
    const ExportResult t = exportMesh(two, path("two.ply"), o);
    QCOMPARE(t.warnings.size(), size_t(1));
    QVERIFY2(t.warnings[0].find("1 of their 2 textures") != std::string::npos, t.warnings[0].c_str());
    MeshData one = m;
    one.submeshes = {{0, uint32_t(one.indices.size()), 0}};
    QVERIFY(exportMesh(one, path("one.ply"), o).warnings.empty());
    for (const ExportFormat f : {ExportFormat::Obj, ExportFormat::Glb}) {
      o.format = f;
      const ExportResult k = exportMesh(m, path(f == ExportFormat::Obj ? "two.obj" : "two.glb"), o);
      QVERIFY2(k.ok() && k.warnings.empty(), k.error.c_str());
    }
  }

  void refusalsWriteNothing() {
    const MeshData m = scanPatch();
    ExportOptions o;
    const std::string missing = path("no/such/folder/x.obj");
    ExportResult r = exportMesh(m, missing, o);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("does not exist") != std::string::npos, r.error.c_str());
    MeshData empty;
    r = exportMesh(empty, path("empty.obj"), o);
    QVERIFY(!r.ok());
    QVERIFY(!fs::exists(path("empty.obj")));
    // A texture with neither bytes nor pixels: refused, and none of the
    // files the OBJ would have had is left behind (temporaries included).
    MeshData broken = scanPatch();
    broken.textures[0].rgba.clear();
    const auto before = std::distance(fs::directory_iterator(tmp_.path().toStdString()), fs::directory_iterator());
    r = exportMesh(broken, path("broken.obj"), o);
    QVERIFY(!r.ok());
    QVERIFY2(r.error.find("rock.png") != std::string::npos, r.error.c_str());
    QCOMPARE(std::distance(fs::directory_iterator(tmp_.path().toStdString()), fs::directory_iterator()), before);
  }
};

QTEST_GUILESS_MAIN(TestMeshExport)
#include "test_mesh_export.moc"
