// Files cut short, and files that shrink, grow or change while they are
// read, for every reader of hs_mesh: OBJ, MTL, georeferencing sidecars,
// textures and the byte reading under them. Each must end in a clean error
// naming the file, or a warning naming it when what was read may be cut
// short; never a signal (a mapped file that shrinks gives SIGBUS), and
// never a short mesh without a word.
#include <QTemporaryDir>
#include <QtTest>

#include <OpenImageIO/imageio.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "file_bytes.h"
#include "mesh/byte_source.h"
#include "mesh/georef_sidecar.h"
#include "mesh/mesh_import.h"
#include "mesh/mtl_reader.h"
#include "mesh/ply_check.h"
#include "mesh/texture_decode.h"
#include "truncation.h"

using namespace hs::mesh;
using hs::test::cutLengths;
using hs::test::readFile;
using hs::test::writeFile;

namespace {

const std::string kData = HS_TEST_DATA_DIR "/mesh";

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// White-space separated words in `s`.
size_t tokenCount(const std::string& s) {
  size_t n = 0;
  for (size_t i = 0; i < s.size(); ++i)
    n += !std::isspace(static_cast<unsigned char>(s[i])) && (i == 0 || std::isspace(static_cast<unsigned char>(s[i - 1])));
  return n;
}

bool anyWarning(const ImportReport& r, const std::string& a, const std::string& b) {
  for (const auto& w : r.warnings)
    if (contains(w, a) && contains(w, b)) return true;
  return false;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

// Whether the last line of `text` holds anything but blanks: cut there, a
// statement may be incomplete.
bool endsInsideALine(const std::string& text) {
  const size_t start = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  return text.find_first_not_of(" \t\r", start) != std::string::npos;
}

// A small OBJ with every statement the reader handles: decimals to cut in
// the middle of, texture coordinates, normals, a polygon, two materials.
std::string smallObj() {
  return "# cut me\n"
         "mtllib cut.mtl\n"
         "o Tile\n"
         "v 656000.125 5514000.25 300.5\n"
         "v 656002.125 5514000.25 300.75\n"
         "v 656002.125 5514001.5 301.25\n"
         "v 656000.125 5514001.5 301.0\n"
         "v 656001.0 5514002.75 302.125\n"
         "vt 0.125 0.25\nvt 0.875 0.25\nvt 0.875 0.75\nvt 0.125 0.75\nvt 0.5 1.0\n"
         "vn 0 0 1\n"
         "usemtl stone\n"
         "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
         "usemtl moss\n"
         "f 4/4/1 3/3/1 5/5/1\n"
         "f -2/-2/1 -3/-3/1 -1/-1/1\n";
}

// An OBJ of about `quads` * 200 bytes with UTM coordinates: big enough
// that reading it takes a while, so a file changing under it is noticed.
std::string gridObj(int side) {
  std::string text;
  char line[128];
  for (int y = 0; y <= side; ++y)
    for (int x = 0; x <= side; ++x) {
      std::snprintf(line, sizeof line, "v %.3f %.3f %.3f\nvt %.6f %.6f\n", 656000.0 + x * 0.5, 5514000.0 + y * 0.5,
                    300.0 + 0.01 * ((x * 7 + y * 3) % 50), double(x) / side, double(y) / side);
      text += line;
    }
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int a = y * (side + 1) + x + 1, b = a + 1, c = a + side + 2, d = a + side + 1;
      std::snprintf(line, sizeof line, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, a, b, b, c, c, a, a, c, c, d, d);
      text += line;
    }
  return text;
}

ImportOptions objReader() {
  ImportOptions o;
  o.reader = Reader::Obj;
  o.up = UpAxis::Z;
  return o;
}

}  // namespace

class TestMeshTruncation : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const std::string& name) { return tmp_.filePath(QString::fromStdString(name)).toStdString(); }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    // A JPEG of the checker: libjpeg decodes a cut JPEG "successfully",
    // filling the missing part with grey, and only warns.
    Texture checker;
    std::string error;
    QVERIFY2(decodeTextureFile(kData + "/checker_4x2.png", checker, error), error.c_str());
    auto out = OIIO::ImageOutput::create(path("checker.jpg"));
    QVERIFY(out);
    QVERIFY(out->open(path("checker.jpg"), OIIO::ImageSpec(checker.width, checker.height, 4, OIIO::TypeDesc::UINT8)));
    QVERIFY(out->write_image(OIIO::TypeDesc::UINT8, checker.rgba.data()));
    QVERIFY(out->close());
  }

  // ---- OBJ ---------------------------------------------------------------------

  // Cut at every byte: an error naming the file, or a mesh with a warning
  // naming it whenever the cut fell inside a line (`v 1 2 3.25` cut to
  // `v 1 2 3.` still parses). Only a cut at a line end leaves a shorter
  // OBJ that no reader can tell from a whole one.
  void objCutAtEveryByte() {
    writeFile(path("cut.mtl"), "newmtl stone\nKd 0.5 0.5 0.5\nnewmtl moss\nKd 0.25 0.5 0.25\n");
    const std::string text = smallObj();
    const std::string p = path("cut.obj");
    size_t errors = 0, warned = 0, clean = 0;
    for (size_t n : cutLengths(text.size(), 1)) {
      const std::string cut = text.substr(0, n);
      writeFile(p, cut);
      const ImportResult r = importMesh(p, objReader());
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + ": ";
      if (!r.ok()) {
        QVERIFY2(!r.cancelled, where + r.error.c_str());
        QVERIFY2(contains(r.error, p), where + r.error.c_str());
        ++errors;
      } else if (endsInsideALine(cut)) {
        QVERIFY2(anyWarning(r.report, p, "cut short"), where + joined(r.report.warnings).c_str());
        ++warned;
      } else {
        QVERIFY2(!anyWarning(r.report, p, "cut short"), where + joined(r.report.warnings).c_str());
        ++clean;
      }
    }
    qInfo("OBJ cut at %zu lengths: %zu errors, %zu meshes with a warning, %zu cut at a line end", text.size(), errors,
          warned, clean);
    QVERIFY(errors > 0 && warned > 0 && clean > 0);
  }

  // The reader's first progress report comes between its two passes over
  // the file: cut the file there, so the second pass finds it shorter
  // (with a file mapping this was SIGBUS).
  void objThatShrinksBetweenPassesIsAnError() {
    const std::string text = gridObj(60);
    const std::string p = path("shrinks.obj");
    writeFile(p, text);
    bool cut = false;
    hs::Progress progress([&](double, std::string_view) {
      if (!cut) QCOMPARE(::truncate(p.c_str(), off_t(text.size() / 3)), 0);
      cut = true;
    });
    const ImportResult r = importMesh(p, objReader(), &progress);
    QVERIFY(cut);
    QVERIFY(!r.ok());
    QVERIFY2(contains(r.error, p) && contains(r.error, "while it was read"), r.error.c_str());
  }

  // Grown, or rewritten with other statements in the same bytes, between
  // the passes: the counts of the first pass no longer hold.
  void objThatChangesBetweenPassesIsAnError_data() {
    QTest::addColumn<bool>("sameSize");
    QTest::newRow("grown") << false;
    QTest::newRow("rewritten, same size") << true;
  }
  void objThatChangesBetweenPassesIsAnError() {
    QFETCH(bool, sameSize);
    const std::string text = gridObj(60);
    const std::string p = path("changes.obj");
    writeFile(p, text);
    bool changed = false;
    hs::Progress progress([&](double, std::string_view) {
      if (changed) return;
      changed = true;
      if (!sameSize) {
        writeFile(p, text + text);
        return;
      }
      // Every face line becomes a vertex line of the same length: more
      // vertices than the first pass made room for.
      std::string other = text;
      for (size_t at = other.find("\nf "); at != std::string::npos; at = other.find("\nf ", at + 1)) {
        const size_t end = other.find('\n', at + 1);
        std::string line = "\nv 1 2 3";
        line.resize(end - at, ' ');
        other.replace(at, end - at, line);
      }
      QCOMPARE(other.size(), text.size());
      writeFile(p, other);
    });
    const ImportResult r = importMesh(p, objReader(), &progress);
    QVERIFY(changed);
    QVERIFY(!r.ok());
    QVERIFY2(contains(r.error, p) && contains(r.error, "changed while it was read"), r.error.c_str());
  }

  // Another thread cuts the file and writes it back while it is imported
  // again and again: every import gives an error naming the file, or the
  // mesh of what the file held at one moment: the whole file, or a part of
  // it from its start (a write in progress shows a file growing page by
  // page), never a mix of two moments.
  void objShrinkingAndGrowingUnderTheReader() {
    const std::string text = gridObj(150);  // 45k triangles, ~2 MB
    const std::string p = path("flapping.obj");
    writeFile(p, text);
    ImportOptions o = objReader();
    o.recenter = false;  // a part of the file then gives a part of the mesh's arrays
    const ImportResult whole = importMesh(p, o);
    QVERIFY2(whole.ok(), whole.error.c_str());
    const MeshData& w = *whole.mesh;
    // A file read while it was being written back can end inside a face
    // line (said by a warning); that face may then read as another one
    // (`f 7/7 8/8 91/91` cut to `f 7/7 8/8 9`), with a vertex of its own:
    // the last triangle and vertex are then left out of the comparison.
    auto startsLikeWhole = [&](const ImportResult& r) {
      const MeshData& m = *r.mesh;
      const size_t slack = anyWarning(r.report, p, "cut short") ? 1 : 0;
      const size_t nv = m.positions.size() - std::min(m.positions.size(), slack);
      const size_t ni = m.indices.size() - std::min(m.indices.size(), 3 * slack);
      return nv <= w.positions.size() && ni <= w.indices.size() && m.uvs.size() == m.positions.size() &&
             std::equal(m.positions.begin(), m.positions.begin() + long(nv), w.positions.begin()) &&
             std::equal(m.uvs.begin(), m.uvs.begin() + long(nv), w.uvs.begin()) &&
             std::equal(m.indices.begin(), m.indices.begin() + long(ni), w.indices.begin());
    };
    const size_t shortLength = text.find('\n', text.size() / 3) + 4;  // inside a line
    size_t errors = 0, wholes = 0, parts = 0;
    {
      hs::test::ShrinkAndGrow flapping(p, text, shortLength);
      QVERIFY(flapping.started());
      for (int i = 0; i < 25; ++i) {
        const ImportResult r = importMesh(p, o);
        if (!r.ok()) {
          QVERIFY2(contains(r.error, p), r.error.c_str());
          ++errors;
          continue;
        }
        QVERIFY2(startsLikeWhole(r), "the mesh is not what the file held at any one moment");
        if (r.mesh->indices.size() == w.indices.size()) ++wholes;
        else ++parts;
      }
      qInfo("25 imports while the file was cut and rewritten %zu times: %zu errors, %zu whole, %zu a part",
            flapping.cycles(), errors, wholes, parts);
    }
    const ImportResult after = importMesh(p, o);
    QVERIFY2(after.ok(), after.error.c_str());
    QCOMPARE(contentHash(*after.mesh), contentHash(w));
  }

  // The file is read in pieces of 256 kB (line_blocks.h); text in memory is
  // not copied. Both give the same mesh and report, with lines longer than
  // a piece (a 600 kB comment, a 40,000-corner polygon) and a last line
  // without a line end.
  void fileAndMemoryReadTheSame() {
    std::string text = gridObj(150);
    const size_t middle = text.find('\n', text.size() / 2) + 1;
    std::string longPolygon = "f";
    for (int i = 0; i < 40000; ++i) longPolygon += " " + std::to_string(1 + i % 5000);
    text.insert(middle, "# " + std::string(600 << 10, 'x') + "\n" + longPolygon + "\n");
    text += "v 656000.5 5514000.5 301.25";  // no line end
    const std::string p = path("pieces.obj");
    writeFile(p, text);
    const ImportResult fromFile = importMesh(p, objReader());
    const ImportResult fromMemory = importObjFromMemory(text, p, tmp_.path().toStdString(), objReader());
    QVERIFY2(fromFile.ok(), fromFile.error.c_str());
    QVERIFY2(fromMemory.ok(), fromMemory.error.c_str());
    QCOMPARE(contentHash(*fromFile.mesh), contentHash(*fromMemory.mesh));
    QCOMPARE(fromFile.report.trianglesIn, fromMemory.report.trianglesIn);
    QCOMPARE(fromFile.report.trianglesIn, size_t(150 * 150 * 2 + 39998));
    QCOMPARE(fromFile.report.warnings, fromMemory.report.warnings);
    QVERIFY2(anyWarning(fromFile.report, p, "cut short"), joined(fromFile.report.warnings).c_str());
  }

  // ---- MTL ---------------------------------------------------------------------

  void mtlCutAtEveryByte() {
    const std::string text =
        "newmtl stone\nKd 0.25 0.5 0.75\nd 0.5\nmap_Kd -s 1 1 1 stone atlas.png\nnewmtl moss\nKd 0.125 0.625 0.375\n";
    const std::string p = path("every.mtl");
    std::string error;
    for (size_t n : cutLengths(text.size(), 1)) {
      const std::string cut = text.substr(0, n);
      writeFile(p, cut);
      std::vector<MtlMaterial> out;
      std::vector<std::string> warnings;
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + ": ";
      if (!readMtl(p, out, error, &warnings)) {
        QVERIFY2(contains(error, p), where + error.c_str());
        continue;
      }
      if (endsInsideALine(cut)) {
        QVERIFY2(warnings.size() == 1 && contains(warnings[0], p) && contains(warnings[0], "cut short"),
                 where + joined(warnings).c_str());
      } else {
        QVERIFY2(warnings.empty(), where + joined(warnings).c_str());
      }
    }
  }

  // ---- georeferencing sidecars ------------------------------------------------------

  void sidecarCutAtEveryByte_data() {
    QTest::addColumn<std::string>("name");
    QTest::addColumn<std::string>("text");
    QTest::newRow("pix4d") << std::string("tile_offset.xyz") << std::string("656000.125 5514000.25 300.125\n");
    QTest::newRow("odm") << std::string("odm_georeferencing_model_geo.txt")
                         << std::string("WGS84 UTM 32N\n656000.125 5514000.25\n");
  }
  void sidecarCutAtEveryByte() {
    QFETCH(std::string, name);
    QFETCH(std::string, text);
    const std::string p = path(name);
    writeFile(p, text);
    GeoOffset whole;
    std::string error;
    QVERIFY2(readGeoOffsetFile(p, whole, error), error.c_str());
    QVERIFY(whole.warning.empty());
    for (size_t n : cutLengths(text.size(), 1)) {
      writeFile(p, text.substr(0, n));
      GeoOffset g;
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + ": ";
      if (!readGeoOffsetFile(p, g, error)) {
        QVERIFY2(contains(error, p), where + error.c_str());
        continue;
      }
      // Every cut that still reads stops inside the offset's line (the
      // whole text is the only one ending after it).
      QVERIFY2(contains(g.warning, p) && contains(g.warning, "cut short"), where + g.warning.c_str());
    }
    // And the warning reaches the import report.
    writeFile(path("tile.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeFile(p, text.substr(0, text.size() - 2));
    ImportOptions o = objReader();
    o.geoOffsetMode = ImportOptions::GeoOffsetMode::File;
    o.geoOffsetFile = p;
    const ImportResult r = importMesh(path("tile.obj"), o);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY2(anyWarning(r.report, p, "cut short"), joined(r.report.warnings).c_str());
    std::remove(p.c_str());
  }

  // ---- textures ------------------------------------------------------------------

  void textureCutAtEveryByte_data() {
    QTest::addColumn<std::string>("file");
    QTest::newRow("png") << kData + "/checker_4x2.png";
    QTest::newRow("jpeg") << path("checker.jpg");
  }
  void textureCutAtEveryByte() {
    QFETCH(std::string, file);
    const std::string bytes = readFile(file);
    QVERIFY(bytes.size() > 50);
    const std::string p = path("cut_" + file.substr(file.rfind('/') + 1));
    Texture whole;
    std::string error;
    QVERIFY2(decodeTextureFile(file, whole, error), error.c_str());
    size_t refused = 0;
    for (size_t n : cutLengths(bytes.size(), 1)) {
      writeFile(p, bytes.substr(0, n));
      Texture t;
      if (decodeTextureFile(p, t, error)) {
        // Only the end marker may be missing (PNG's IEND, the last 12
        // bytes): the pixels must then all be there, as decoded whole.
        QVERIFY2(n >= bytes.size() - 12, qPrintable(QString("cut at byte %1 decoded").arg(n)));
        QVERIFY(t.rgba == whole.rgba);
        continue;
      }
      QVERIFY2(contains(error, p), error.c_str());
      ++refused;
    }
    QVERIFY(refused >= bytes.size() - 12);
  }

  // ---- PLY, before Assimp reads it ------------------------------------------------

  // Assimp 5.2.5 loops forever on a PLY header cut short: every cut of a
  // binary PLY (header or body) and every cut of an ASCII PLY's header is
  // refused before it gets there; an ASCII body is Assimp's to judge.
  void plyCutAtEveryByte_data() {
    QTest::addColumn<std::string>("format");
    QTest::newRow("binary little endian") << std::string("binary_little_endian");
    QTest::newRow("binary big endian") << std::string("binary_big_endian");
    QTest::newRow("ascii") << std::string("ascii");
  }
  void plyCutAtEveryByte() {
    QFETCH(std::string, format);
    const bool ascii = format == "ascii";
    const bool big = format == "binary_big_endian";
    std::string text = "ply\nformat " + format +
                       " 1.0\ncomment two triangles\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nproperty uchar red\nelement face 2\nproperty list uchar int vertex_indices\n"
                       "property short flags\nend_header\n";
    const size_t headerEnd = text.size();
    auto put = [&](const void* p, size_t n) {
      const char* b = static_cast<const char*>(p);
      for (size_t i = 0; i < n; ++i) text += b[big ? n - 1 - i : i];
    };
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& v : xyz) {
      if (ascii) text += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 200\n";
      else {
        for (float c : v) put(&c, 4);
        text += char(200);
      }
    }
    for (const auto& f : faces) {
      const uint8_t three = 3;
      const int16_t flags = 7;
      if (ascii) text += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " 7\n";
      else {
        put(&three, 1);
        for (int i : f) put(&i, 4);
        put(&flags, 2);
      }
    }
    const std::string p = path("cut.ply");
    writeFile(p, text);
    std::string error;
    QVERIFY2(checkPlyComplete(p, error), error.c_str());
    for (size_t n : cutLengths(text.size(), 1)) {
      writeFile(p, text.substr(0, n));
      const bool headerWhole = n >= headerEnd;
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + ": ";
      // An ASCII body is checked token by token: a cut that leaves every
      // value (only the last line end gone, or inside the last number)
      // cannot be told from a whole file; any other cut is refused.
      if (ascii && headerWhole && tokenCount(text.substr(headerEnd, n - headerEnd)) ==
                                      tokenCount(text.substr(headerEnd))) {
        QVERIFY2(checkPlyComplete(p, error), where + error.c_str());
        continue;
      }
      QVERIFY2(!checkPlyComplete(p, error), where.constData());
      // The own reader's words (the check uses its parser): cut in a row,
      // "cut short"; a list longer than the bytes left, "past the end of
      // the file"; the header's counts no longer fit the bytes left,
      // "truncated".
      QVERIFY2(contains(error, p) && (contains(error, "cut short") || contains(error, "past the end of the file") ||
                                      contains(error, "truncated")),
               where + error.c_str());
    }
  }

  // ---- the byte reading under them ---------------------------------------------------

  // readWholeFile (MTL, sidecars, textures) on a file another thread cuts
  // and writes back: what the file held at one moment (the whole, the cut
  // file, or the cut file with part of the rest written back), or an error
  // naming it.
  void wholeFileReadsWhileTheFileShrinksAndGrows() {
    std::string text(3 << 20, '\0');
    for (size_t i = 0; i < text.size(); ++i) text[i] = char('a' + i % 23);
    const std::string p = path("flapping.bin");
    writeFile(p, text);
    const size_t shortLength = text.size() / 2 + 7;
    size_t errors = 0, wholes = 0, shorts = 0;
    {
      hs::test::ShrinkAndGrow flapping(p, text, shortLength);
      QVERIFY(flapping.started());
      for (int i = 0; i < 200; ++i) {
        std::string got, error;
        if (!readWholeFile(p, got, error)) {
          QVERIFY2(contains(error, p) && contains(error, "changed while it was read"), error.c_str());
          ++errors;
        } else if (got.size() == text.size()) {
          QVERIFY(got == text);
          ++wholes;
        } else {
          QVERIFY(got.size() >= shortLength);
          QVERIFY(text.compare(0, got.size(), got) == 0);
          ++shorts;
        }
      }
      qInfo("200 reads while the file was cut and rewritten %zu times: %zu errors, %zu whole, %zu short", flapping.cycles(),
            errors, wholes, shorts);
    }
  }

  void byteSourceRefusesWhatIsNotAFile() {
    ByteSource s;
    std::string error;
    QVERIFY(!s.open(path("missing.obj"), error));
    QVERIFY2(contains(error, path("missing.obj")) && contains(error, "not found"), error.c_str());
    QVERIFY(!s.open(tmp_.path().toStdString(), error));
    QVERIFY2(contains(error, "directory"), error.c_str());
    const std::string fifo = path("fifo.obj");
    QCOMPARE(::mkfifo(fifo.c_str(), 0600), 0);
    QVERIFY(!s.open(fifo, error));  // and does not block waiting for a writer
    QVERIFY2(contains(error, fifo) && contains(error, "not a regular file"), error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestMeshTruncation)
#include "test_mesh_truncation.moc"
