// Mesh readers on hostile files (issue 10's campaign): counts that the file
// cannot hold are refused before anything is allocated, with the element
// and place; files cut short are errors, not short meshes; what a file
// declares is compared with what was imported (a warning, or an error with
// `strict`); paths that are not regular files (devices, FIFOs, directories)
// never block or spin a reader. Every fixture is a 10 x 10 grid of quads
// (200 triangles, 121 vertices) this test writes in the format at hand.
#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QtTest>

#include <sys/stat.h>

#include <cstring>
#include <string>
#include <vector>

#include "file_bytes.h"
#include "mesh/mesh_import.h"
#include "meshproc/report_json.h"

using namespace hs::mesh;
using hs::test::writeFile;

namespace {

constexpr int kN = 10;
constexpr size_t kTriangles = 2 * kN * kN, kVertices = (kN + 1) * (kN + 1);

struct Grid {
  std::vector<std::array<float, 3>> v;
  std::vector<std::array<uint32_t, 3>> t;
};

Grid grid() {
  Grid g;
  for (int y = 0; y <= kN; ++y)
    for (int x = 0; x <= kN; ++x) g.v.push_back({x * 0.1f, y * 0.1f, 0.01f * float((x * 7 + y * 3) % 5)});
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const uint32_t a = uint32_t(y * (kN + 1) + x);
      g.t.push_back({a, a + 1, a + kN + 2});
      g.t.push_back({a, a + kN + 2, a + kN + 1});
    }
  return g;
}

std::string num(float f) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(f));
  return b;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string objText(const Grid& g) {
  std::string s;
  for (const auto& p : g.v) s += "v " + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
  for (const auto& f : g.t)
    s += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1) + "\n";
  return s;
}

std::string plyHeader(const char* format, const std::string& vertices, const std::string& faces) {
  return std::string("ply\nformat ") + format + " 1.0\nelement vertex " + vertices +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string plyAsciiBody(const Grid& g, size_t faces) {
  std::string s;
  for (const auto& p : g.v) s += num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
  for (size_t i = 0; i < faces; ++i)
    s += "3 " + std::to_string(g.t[i][0]) + " " + std::to_string(g.t[i][1]) + " " + std::to_string(g.t[i][2]) + "\n";
  return s;
}

std::string plyBinaryBody(const Grid& g) {
  std::string s;
  for (const auto& p : g.v) put(s, p);
  for (const auto& f : g.t) {
    put(s, uint8_t(3));
    for (uint32_t i : f) put(s, int32_t(i));
  }
  return s;
}

std::string stlAscii(const Grid& g, size_t facets, bool endSolid) {
  std::string s = "solid grid\n";
  for (size_t i = 0; i < facets; ++i) {
    s += "facet normal 0 0 1\n outer loop\n";
    for (uint32_t k : g.t[i]) s += "  vertex " + num(g.v[k][0]) + " " + num(g.v[k][1]) + " " + num(g.v[k][2]) + "\n";
    s += " endloop\nendfacet\n";
  }
  return endSolid ? s + "endsolid grid\n" : s;
}

std::string stlBinary(const Grid& g, uint32_t count) {
  std::string s(80, '\0');
  put(s, count);
  for (const auto& f : g.t) {
    put(s, std::array<float, 3>{0, 0, 1});
    for (uint32_t k : f) put(s, g.v[k]);
    put(s, uint16_t(0));
  }
  return s;
}

// The glTF JSON for the grid: positions then uint32 indices in one buffer.
// `indexCount` overrides the index accessor's count.
std::string gltfJson(const std::string& bufferUri, size_t positionBytes, size_t indexBytes, uint64_t indexCount) {
  const std::string uri = bufferUri.empty() ? "" : "\"uri\": \"" + bufferUri + "\", ";
  return "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}],"
         " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1}]}],"
         " \"buffers\": [{" + uri + "\"byteLength\": " + std::to_string(positionBytes + indexBytes) + "}],"
         " \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": " + std::to_string(positionBytes) +
         "}, {\"buffer\": 0, \"byteOffset\": " + std::to_string(positionBytes) + ", \"byteLength\": " +
         std::to_string(indexBytes) + "}],"
         " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": " + std::to_string(kVertices) +
         ", \"type\": \"VEC3\", \"min\": [0, 0, 0], \"max\": [1, 1, 0.04]},"
         " {\"bufferView\": 1, \"componentType\": 5125, \"count\": " + std::to_string(indexCount) +
         ", \"type\": \"SCALAR\"}]}";
}

std::string gltfBuffer(const Grid& g, bool oneIndexOutOfRange) {
  std::string s;
  for (const auto& p : g.v) put(s, p);
  for (size_t i = 0; i < g.t.size(); ++i)
    for (int k = 0; k < 3; ++k) put(s, oneIndexOutOfRange && i + 1 == g.t.size() && k == 2 ? 100000u : g.t[i][k]);
  return s;
}

// `jsonLengthField` overrides the JSON chunk's length when not 0.
std::string glb(const std::string& json, const std::string& bin, uint32_t jsonLengthField) {
  std::string j = json, b = bin;
  while (j.size() % 4) j += ' ';
  while (b.size() % 4) b += '\0';
  std::string s = "glTF";
  put(s, uint32_t(2));
  put(s, uint32_t(12 + 8 + j.size() + 8 + b.size()));
  put(s, jsonLengthField ? jsonLengthField : uint32_t(j.size()));
  s += "JSON" + j;
  put(s, uint32_t(b.size()));
  s += std::string("BIN\0", 4) + b;
  return s;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string joined(const ImportReport& r) {
  std::string s;
  for (const auto& w : r.warnings) s += w + " | ";
  return s;
}

bool anyWarning(const ImportReport& r, std::initializer_list<const char*> parts) {
  for (const auto& w : r.warnings) {
    bool all = true;
    for (const char* p : parts) all = all && contains(w, p);
    if (all) return true;
  }
  return false;
}

}  // namespace

class TestMeshReliability : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  Grid g_ = grid();

  std::string path(const char* name) const { return tmp_.filePath(name).toStdString(); }
  std::string write(const char* name, const std::string& bytes) const {
    const std::string p = path(name);
    writeFile(p, bytes);
    return p;
  }

  // importMesh must refuse `p` with an error naming it and every part.
  void expectRefused(const std::string& p, std::initializer_list<const char*> parts, const ImportOptions& o = {}) {
    QElapsedTimer clock;
    clock.start();
    const ImportResult r = importMesh(p, o);
    QVERIFY2(!r.ok(), (p + ": imported " + std::to_string(r.report.trianglesOut) + " triangles").c_str());
    QVERIFY2(contains(r.error, p), r.error.c_str());
    for (const char* part : parts) QVERIFY2(contains(r.error, part), (r.error + " (wanted: " + part + ")").c_str());
    // Refused from the header, not after allocating or reading what it claims.
    QVERIFY2(clock.elapsed() < 5000, (std::to_string(clock.elapsed()) + " ms").c_str());
  }

  // importMesh must read `p` whole: 200 triangles, declared and imported alike.
  void expectWhole(const std::string& p, const char* declaredBy, const ImportOptions& o = {}) {
    const ImportResult r = importMesh(p, o);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.trianglesOut, kTriangles);
    QCOMPARE(r.report.declaredTriangles, kTriangles);
    QVERIFY2(contains(r.report.declaredBy, declaredBy), r.report.declaredBy.c_str());
    QVERIFY2(r.report.warnings.empty(), joined(r.report).c_str());
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  // ---- every format read whole, declared = imported, also with strict ----------------

  void intactFilesDeclareWhatTheyHold() {
    ImportOptions strict;
    strict.strict = true;
    for (const ImportOptions& o : {ImportOptions{}, strict}) {
      expectWhole(write("ok.obj", objText(g_)), "OBJ faces", o);
      expectWhole(write("ok_ascii.ply", plyHeader("ascii", "121", "200") + plyAsciiBody(g_, 200)), "PLY face", o);
      expectWhole(write("ok_bin.ply", plyHeader("binary_little_endian", "121", "200") + plyBinaryBody(g_)),
                  "PLY face", o);
      expectWhole(write("ok_ascii.stl", stlAscii(g_, 200, true)), "ASCII STL: 200 facets", o);
      expectWhole(write("ok_bin.stl", stlBinary(g_, 200)), "binary STL header: 200", o);
      const std::string buf = gltfBuffer(g_, false);
      expectWhole(write("ok.glb", glb(gltfJson("", kVertices * 12, 600 * 4, 600), buf, 0)), "glTF accessors", o);
      write("ok.bin", buf);
      expectWhole(write("ok.gltf", gltfJson("ok.bin", kVertices * 12, 600 * 4, 600)), "glTF accessors", o);
    }
  }

  // The report JSON (meshproc/report_json.h, the one serialiser) carries
  // the declared count beside the imported one, and reads it back.
  void reportJsonHasDeclaredAndImported() {
    write("oor.bin", gltfBuffer(g_, true));
    const ImportResult r = importMesh(write("oor.gltf", gltfJson("oor.bin", kVertices * 12, 600 * 4, 600)));
    QVERIFY2(r.ok(), r.error.c_str());
    const hs::Json j = toJson(r.report);
    QCOMPARE(j["declared"]["triangles"].get<size_t>(), kTriangles);
    QCOMPARE(j["triangles_out"].get<size_t>(), kTriangles - 1);
    QVERIFY(contains(j["declared"]["by"].get<std::string>(), "glTF accessors"));
    std::string error;
    hs::JsonReader reader(error);
    ImportReport back;
    QVERIFY2(fromJson(reader, j, "", back), error.c_str());
    QCOMPARE(back.declaredTriangles, kTriangles);
    QCOMPARE(back.declaredBy, r.report.declaredBy);
  }

  // ---- silent losses of the campaign ---------------------------------------------------

  // Was: 20 of 200 triangles, exit 0.
  void asciiStlCutShortIsAnError() {
    expectRefused(write("cut.stl", stlAscii(g_, 20, false)), {"cut short", "20 complete facets", "endsolid"});
    // Cut inside a facet: the facet and its byte are named.
    const std::string whole = stlAscii(g_, 200, true);
    expectRefused(write("cut2.stl", whole.substr(0, whole.find("vertex", whole.size() / 2))),
                  {"cut short", "has no 'endfacet'", "byte"});
    // A damaged keyword is not called a cut (found by the campaign's byte flips).
    std::string flipped = whole;
    flipped[flipped.find("facet normal", 1000)] = '#';
    expectRefused(write("flipped.stl", flipped), {"damaged", "200 'endfacet' but only 199 'facet'"});
  }

  // Was: 199 of 200, exit 0, no warning (the same fault in OBJ warned).
  void gltfWithAnOutOfRangeIndexWarnsOrFailsStrict() {
    write("oor.bin", gltfBuffer(g_, true));
    const std::string p = write("oor.gltf", gltfJson("oor.bin", kVertices * 12, 600 * 4, 600));
    const ImportResult r = importMesh(p);
    QVERIFY2(r.ok(), r.error.c_str());
    QCOMPARE(r.report.trianglesOut, kTriangles - 1);
    QVERIFY2(anyWarning(r.report, {"declares 200 triangles", "199 were imported"}), joined(r.report).c_str());
    ImportOptions strict;
    strict.strict = true;
    expectRefused(p, {"declares 200 triangles", "199 were imported", "--strict"}, strict);
  }

  // The OBJ reader's dropped faces go through the same comparison.
  void objWithAnOutOfRangeIndexWarnsOrFailsStrict() {
    const std::string p = write("oor.obj", objText(g_) + "f 1 2 999\n");
    const ImportResult r = importMesh(p);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY2(anyWarning(r.report, {"declares 201 triangles", "200 were imported", "out of range"}),
             joined(r.report).c_str());
    ImportOptions strict;
    strict.strict = true;
    expectRefused(p, {"declares 201 triangles", "--strict"}, strict);
  }

  // Was: read as 1 face ("1e9" through operator>>).
  void plyCountThatIsNotAWholeNumber() {
    expectRefused(write("e9.ply", plyHeader("ascii", "121", "1e9") + plyAsciiBody(g_, 200)),
                  {":7:", "element face", "'1e9'", "not a whole number"});
    expectRefused(write("neg.ply", plyHeader("binary_little_endian", "121", "-1") + plyBinaryBody(g_)),
                  {"element face", "'-1'"});
  }

  // Was: the worker grew about 220 MB/s until killed.
  void plyCountsPastTheFileAreRefusedFromTheHeader() {
    expectRefused(write("huge.ply", plyHeader("binary_little_endian", "99999999999999999999", "200") + plyBinaryBody(g_)),
                  {"element vertex", "too large"});
    expectRefused(write("big_ascii.ply", plyHeader("ascii", "999999999", "200") + plyAsciiBody(g_, 200)),
                  {"element vertex declares 999999999 rows", "bytes follow"});
    expectRefused(write("big_bin.ply", plyHeader("binary_little_endian", "121", "4294967295") + plyBinaryBody(g_)),
                  {"element face", "4294967295"});
    // Found by fuzz_ply_check: an element without properties and a huge
    // count looped over its empty rows for ever.
    const std::string ascii = plyHeader("ascii", "121", "200");
    expectRefused(write("empty_rows.ply", ascii.substr(0, ascii.find("element vertex")) +
                                              "element nothing 17774258721798138539\n" +
                                              ascii.substr(ascii.find("element vertex")) + plyAsciiBody(g_, 200)),
                  {"element nothing declares 17774258721798138539 rows without properties"});
  }

  // Was: 200 triangles over 3 vertices, exit 0.
  void asciiPlyCutShortIsAnError() {
    expectRefused(write("three.ply", plyHeader("ascii", "121", "200") + "0 0 0\n1 0 0\n0 1 0\n"),
                  {"element vertex declares 121 rows"});
    const std::string whole = plyHeader("ascii", "121", "200") + plyAsciiBody(g_, 200);
    expectRefused(write("half.ply", whole.substr(0, whole.size() * 3 / 4)), {"cut short", "in face", "of 200"});
  }

  // Was: 250 triangles imported (50 made up).
  void plyHeaderClaimingMoreFacesThanTheBodyHolds() {
    expectRefused(write("250.ply", plyHeader("ascii", "121", "250") + plyAsciiBody(g_, 200)),
                  {"cut short", "face 201 of 250"});
    expectRefused(write("250b.ply", plyHeader("binary_little_endian", "121", "250") + plyBinaryBody(g_)),
                  {"cut short", "of 250"});
  }

  // Fewer faces declared than the body holds: the import is exactly what
  // was declared, and the data left over is said, not dropped silently.
  void plyHeaderClaimingFewerFacesReadsWhatItDeclares() {
    for (const bool ascii : {true, false}) {
      const std::string p = write(ascii ? "150.ply" : "150b.ply",
                                  ascii ? plyHeader("ascii", "121", "150") + plyAsciiBody(g_, 200)
                                        : plyHeader("binary_little_endian", "121", "150") + plyBinaryBody(g_));
      const ImportResult r = importMesh(p);
      QVERIFY2(r.ok(), r.error.c_str());
      QCOMPARE(r.report.declaredTriangles, size_t(150));
      QCOMPARE(r.report.trianglesOut, size_t(150));
      QVERIFY2(anyWarning(r.report, {"the rest is not read"}), joined(r.report).c_str());
    }
  }

  // One PLY parser: the check before Assimp (`--reader assimp`) reads the
  // header and body with the own reader's parser and cursor, so a bad file
  // gets the same message, byte for byte, whichever reader is asked.
  void bothPlyPathsRefuseWithTheSameMessage() {
    const std::string ascii = plyHeader("ascii", "121", "200") + plyAsciiBody(g_, 200);
    const std::string binary = plyHeader("binary_little_endian", "121", "200") + plyBinaryBody(g_);
    const std::string header = plyHeader("ascii", "121", "200");
    const std::pair<const char*, std::string> cases[] = {
        {"twin_e9.ply", plyHeader("ascii", "121", "1e9") + plyAsciiBody(g_, 200)},
        {"twin_neg.ply", plyHeader("binary_little_endian", "121", "-1") + plyBinaryBody(g_)},
        {"twin_huge.ply", plyHeader("binary_little_endian", "99999999999999999999", "200") + plyBinaryBody(g_)},
        {"twin_big.ply", plyHeader("ascii", "999999999", "200") + plyAsciiBody(g_, 200)},
        {"twin_no_end.ply", header.substr(0, header.find("end_header"))},
        {"twin_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n1\n"},
        {"twin_keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 1\nend_header\n"},
        {"twin_format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"},
        {"twin_half.ply", ascii.substr(0, ascii.size() * 3 / 4)},
        {"twin_250.ply", plyHeader("ascii", "121", "250") + plyAsciiBody(g_, 200)},
        {"twin_250b.ply", plyHeader("binary_little_endian", "121", "250") + plyBinaryBody(g_)},
        {"twin_cut_b.ply", binary.substr(0, binary.size() - 7)},
        {"twin_word.ply", ascii.substr(0, ascii.size() - 40) + "zero" + ascii.substr(ascii.size() - 36)},
        {"twin_list.ply", header + plyAsciiBody(g_, 199) + "4000000000 0 1 2\n"},
    };
    ImportOptions assimp;
    assimp.reader = Reader::Assimp;
    for (const auto& [name, bytes] : cases) {
      const std::string p = write(name, bytes);
      const ImportResult own = importMesh(p), checked = importMesh(p, assimp);
      QVERIFY2(!own.ok(), name);
      QVERIFY2(!checked.ok(), name);
      QVERIFY2(own.report.reader == "ply", own.report.reader.c_str());
      QVERIFY2(own.error == checked.error, (own.error + "\n  vs\n" + checked.error).c_str());
      QVERIFY2(contains(own.error, p), own.error.c_str());
    }
  }

  // Issue 11's guard, on Assimp's PLY path: triangle strips are declared
  // by their lists; what Assimp makes of them is compared, never silent.
  void plyTristripsAreDeclaredAndCompared() {
    // Two rows of the grid as one strip per row, restart (-1) between.
    std::string body;
    for (const auto& p : g_.v) body += num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
    std::string strip;
    size_t entries = 0;
    for (int y = 0; y < 2; ++y) {
      if (y) strip += " -1", ++entries;
      for (int x = 0; x <= kN; ++x) {
        strip += " " + std::to_string((y + 1) * (kN + 1) + x) + " " + std::to_string(y * (kN + 1) + x);
        entries += 2;
      }
    }
    body += std::to_string(entries) + strip + "\n";
    const std::string p = write("strips.ply", "ply\nformat ascii 1.0\nelement vertex 121\nproperty float x\n"
                                              "property float y\nproperty float z\nelement tristrips 1\n"
                                              "property list int int vertex_indices\nend_header\n" + body);
    const ImportResult r = importMesh(p);
    // 2 strips of 22 indices: 20 triangles each.
    QCOMPARE(r.report.declaredTriangles, size_t(40));
    QVERIFY(contains(r.report.declaredBy, "tristrips"));
    if (r.ok() && r.report.trianglesOut != 40)
      QVERIFY2(anyWarning(r.report, {"declares 40 triangles"}), joined(r.report).c_str());
  }

  // ---- counts past the file in binary formats -------------------------------------------

  void binaryStlCountAgainstItsSize() {
    expectRefused(write("250.stl", stlBinary(g_, 250)), {"byte 80", "250 triangles", "10084"});
    expectRefused(write("max.stl", stlBinary(g_, 0xffffffffu)), {"byte 80", "4294967295 triangles"});
    // An 80-byte header starting with "solid" is still binary when the sizes agree.
    std::string solidHeader = stlBinary(g_, 200);
    std::memcpy(solidHeader.data(), "solid exported", 14);
    expectWhole(write("solid_bin.stl", solidHeader), "binary STL header: 200");
  }

  // Was: 1.2 GB allocated in 6 s.
  void glbChunkLengthsAgainstTheFile() {
    const std::string buf = gltfBuffer(g_, false);
    expectRefused(write("chunk.glb", glb(gltfJson("", kVertices * 12, 2400, 600), buf, 0xfffffff0u)),
                  {"byte 12", "4294967280"});
    expectRefused(write("count.glb", glb(gltfJson("", kVertices * 12, 2400, 1000000000), buf, 0)),
                  {"accessors[1]", "1000000000 elements", "2400 bytes"});
    const std::string whole = glb(gltfJson("", kVertices * 12, 2400, 600), buf, 0);
    expectRefused(write("cut.glb", whole.substr(0, whole.size() - 100)), {"cut short"});
  }

  // ---- paths that are not files ----------------------------------------------------

  void gltfBuffersThatAreNotFiles() {
    expectRefused(write("dev.gltf", gltfJson("/dev/urandom", kVertices * 12, 2400, 600)),
                  {"buffers[0]", "/dev/urandom", "not a regular file"});
    QVERIFY(QDir(tmp_.path()).mkpath("dirbuf"));
    expectRefused(write("dir.gltf", gltfJson("dirbuf", kVertices * 12, 2400, 600)),
                  {"buffers[0]", "a directory"});
  }

  // Was: the in-process OBJ reader spun on mtllib /dev/urandom.
  void objMaterialLibrariesThatAreNotFiles() {
    QVERIFY(::mkfifo(path("fifo.mtl").c_str(), 0600) == 0);
    QVERIFY(QDir(tmp_.path()).mkpath("dir.mtl"));
    for (const char* lib : {"/dev/urandom", "/dev/zero", "fifo.mtl", "dir.mtl"}) {
      QElapsedTimer clock;
      clock.start();
      const ImportResult r = importMesh(write("lib.obj", std::string("mtllib ") + lib + "\nusemtl a\n" + objText(g_)));
      QVERIFY2(clock.elapsed() < 5000, lib);
      QVERIFY2(r.ok(), r.error.c_str());
      QCOMPARE(r.report.trianglesOut, kTriangles);
      QVERIFY2(anyWarning(r.report, {lib}), (std::string(lib) + ": " + joined(r.report)).c_str());
    }
  }

  void meshPathsThatAreNotFiles() {
    QVERIFY(::mkfifo(path("fifo.ply").c_str(), 0600) == 0);
    expectRefused(path("fifo.ply"), {"not a regular file"});
    QVERIFY(QDir(tmp_.path()).mkpath("folder.glb"));
    expectRefused(path("folder.glb"), {"is a directory"});
    ImportOptions assimp;
    assimp.reader = Reader::Assimp;
    expectRefused("/dev/urandom", {"not a regular file"}, assimp);
  }
};

QTEST_GUILESS_MAIN(TestMeshReliability)
#include "test_mesh_reliability.moc"
