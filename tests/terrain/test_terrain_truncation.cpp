// DEMs (GDAL) and heightmap images (OpenImageIO, raw .r16) cut short: each
// cut file is refused with a message naming it, or (a cut that only lost
// bytes the format does not need) gives the whole terrain, or (a text grid
// cut in its last line) a terrain with a warning that it may be cut short;
// never a part of it, or heights filled in by the decoder, without a word.
#include <QTemporaryDir>
#include <QtTest>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "file_bytes.h"
#include "terrain/dem_import.h"
#include "terrain/heightmap_image.h"
#include "truncation.h"

using namespace hs::terrain;
using hs::test::cutLengths;
using hs::test::readFile;
using hs::test::writeFile;

namespace {

const std::string kDem = std::string(HS_TEST_DATA_DIR) + "/terrain/dem_wgs84.tif";

bool sameHeights(const Heightfield& a, const Heightfield& b) {
  if (a.samplesX() != b.samplesX() || a.samplesY() != b.samplesY()) return false;
  for (int y = 0; y < a.samplesY(); ++y)
    for (int x = 0; x < a.samplesX(); ++x)
      if (a.at(x, y) != b.at(x, y) || a.isHole(x, y) != b.isHole(x, y)) return false;
  return true;
}

// Some 200 cut lengths at most: every byte of a small file.
size_t stepFor(size_t size) { return size / 200 + 1; }

}  // namespace

class TestTerrainTruncation : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string path(const std::string& name) const { return tmp_.filePath(QString::fromStdString(name)).toStdString(); }

  // A small terrain with hills and fractional heights, to export.
  Heightfield hills() const {
    auto t = Heightfield::create(HeightfieldDesc{40, 30, {390.0, 290.0}, {500000.0, 4400000.0, 0.0}, 0.0f, {}});
    if (!t) qFatal("%s", t.error().c_str());
    Heightfield hf = t.take();
    for (int y = 0; y < hf.samplesY(); ++y)
      for (int x = 0; x < hf.samplesX(); ++x) hf.set(x, y, float(100.0 + 20.0 * std::sin(0.2 * x) * std::cos(0.3 * y) + 0.01 * x));
    return hf;
  }

 private slots:
  void initTestCase() { QVERIFY(tmp_.isValid()); }

  void demCutShort_data() {
    QTest::addColumn<std::string>("file");
    QTest::newRow("GeoTIFF fixture (tiled, geographic)") << kDem;
    QTest::newRow("Esri ASCII grid") << path("grid.asc");
  }
  void demCutShort() {
    QFETCH(std::string, file);
    writeFile(path("grid.asc"), "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n"
                                "1.25 2.5 3.75 4\n5 -9999 7 8.5\n9 10 11.125 12.25\n");
    const std::string bytes = readFile(file);
    QVERIFY(!bytes.empty());
    const DemImportResult whole = importDem(file);
    QVERIFY2(whole.ok(), whole.error.c_str());
    const std::string p = path("cut" + file.substr(file.rfind('.')));
    size_t refused = 0;
    for (size_t n : cutLengths(bytes.size(), stepFor(bytes.size()))) {
      writeFile(p, bytes.substr(0, n));
      const DemImportResult r = importDem(p);
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + ": ";
      if (r.ok()) {
        // A text grid cut in its last line reads with a warning that says so.
        bool warned = false;
        for (const auto& w : r.report.warnings) warned |= w.find("cut short") != std::string::npos;
        QVERIFY2(warned || sameHeights(*r.heightfield, *whole.heightfield), where + "a different terrain, no error");
        continue;
      }
      QVERIFY2(!r.cancelled, where + r.error.c_str());
      QVERIFY2(r.error.find(p) != std::string::npos, where + r.error.c_str());
      ++refused;
    }
    QVERIFY(refused > 0);
  }

  void heightmapCutShort_data() {
    QTest::addColumn<std::string>("name");
    QTest::newRow("16-bit PNG") << std::string("hm.png");
    QTest::newRow("EXR") << std::string("hm.exr");
    QTest::newRow("GeoTIFF (importDem)") << std::string("hm.tif");
    QTest::newRow("raw .r16 with its sidecar") << std::string("hm.r16");
    QTest::newRow("8-bit JPEG") << std::string("hm.jpg");
  }
  void heightmapCutShort() {
    QFETCH(std::string, name);
    const std::string file = path(name);
    if (name.ends_with(".jpg")) {
      // Not a format Hybridscape writes, but one it reads: libjpeg decodes a
      // cut JPEG "successfully", filling the rest with grey.
      const Heightfield hf = hills();
      std::vector<uint8_t> grey;
      for (int y = hf.samplesY() - 1; y >= 0; --y)
        for (int x = 0; x < hf.samplesX(); ++x) grey.push_back(uint8_t(std::clamp(hf.at(x, y) + 28.0f, 0.0f, 255.0f)));
      auto out = OIIO::ImageOutput::create(file);
      QVERIFY(out && out->open(file, OIIO::ImageSpec(hf.samplesX(), hf.samplesY(), 1, OIIO::TypeDesc::UINT8)));
      QVERIFY(out->write_image(OIIO::TypeDesc::UINT8, grey.data()) && out->close());
    } else {
      const auto exported = exportHeightmap(hills(), file);
      QVERIFY2(exported.ok(), exported.error().c_str());
    }
    const bool dem = name.ends_with(".tif");
    auto import = [&](const std::string& f) -> Result<Heightfield> {
      if (!dem) return importHeightmap(f);
      DemImportResult r = importDem(f);
      if (!r.ok()) return Result<Heightfield>::failure(r.error);
      return std::move(*r.heightfield);
    };
    const Result<Heightfield> whole = import(file);
    QVERIFY2(whole.ok(), whole.error().c_str());
    const std::string bytes = readFile(file);
    const std::string p = path("cut_" + name);
    if (name.ends_with(".r16")) writeFile(p + ".json", readFile(file + ".json"));
    size_t refused = 0;
    for (size_t n : cutLengths(bytes.size(), stepFor(bytes.size()))) {
      writeFile(p, bytes.substr(0, n));
      const Result<Heightfield> r = import(p);
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + " of " +
                               QByteArray::number(qulonglong(bytes.size())) + ": ";
      if (r.ok()) {
        QVERIFY2(sameHeights(*r, *whole), where + "a different terrain, no error");
        continue;
      }
      QVERIFY2(r.error().find(p) != std::string::npos, where + r.error().c_str());
      ++refused;
    }
    QVERIFY(refused > 0);
  }
};

QTEST_GUILESS_MAIN(TestTerrainTruncation)
#include "test_terrain_truncation.moc"
