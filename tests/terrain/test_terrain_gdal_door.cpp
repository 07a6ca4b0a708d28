// terrain/gdal_door: GDAL and PROJ in a module loaded on first use. This
// suite links hs_terrain only (not GDAL), so it sees what a program sees:
// - no GDAL library is mapped until the first DEM call, and the programs
//   (CLI, editor) do not link it;
// - a DEM read through the module has the file's heights (an ASCII grid
//   written here, checked value by value) and GDAL's inverse-distance fill
//   reaches its hole;
// - without the module, DEM import and GeoTIFF export fail naming where it
//   was looked for, and the inverse-distance fill falls back to diffusion
//   and says so.
#include <QTemporaryDir>
#include <QtTest>

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include "terrain/dem_export.h"
#include "terrain/dem_import.h"
#include "terrain/gdal_door.h"
#include "terrain/nodata_fill.h"
#include "loaded_libraries.h"

using namespace hs;
using namespace hs::terrain;

namespace {

bool gdalMapped() { return test::mappedHere("libgdal"); }

// 5 x 4 heights, north row first as the format has it, one nodata cell.
constexpr int kW = 5, kH = 4;
constexpr float kNodata = -9999.0f;
const float kRows[kH][kW] = {{10, 11, 12, 13, 14}, {20, 21, 22, 23, 24}, {30, 31, kNodata, 33, 34}, {40, 41, 42, 43, 44}};

void writeAsciiGrid(const std::string& path) {
  std::ofstream f(path);
  f << "ncols " << kW << "\nnrows " << kH << "\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value "
    << kNodata << "\n";
  for (const auto& row : kRows) {
    for (float v : row) f << v << ' ';
    f << '\n';
  }
}

}  // namespace

class TestTerrainGdalDoor : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    writeAsciiGrid(path("grid.asc"));
  }

  // First: nothing in this process has touched GDAL yet.
  void aMissingModuleIsNamed() {
    QVERIFY(!gdalMapped());
    const pid_t child = fork();
    QVERIFY(child >= 0);
    if (child == 0) {
      ::setenv("HS_GDAL_MODULE", "/nonexistent/hybridscape-gdal.so", 1);
      const DemImportResult r = importDem(path("grid.asc"));
      HeightfieldDesc desc;
      desc.samplesX = desc.samplesY = 3;
      desc.sizeMetres = {2.0, 2.0};
      auto hf = Heightfield::create(desc);
      const Status s = hf ? exportGeoTiff(*hf, path("out.tif")) : Status::failure("no heightfield");
      auto named = [](const std::string& e) {
        return e.find("the GDAL module hybridscape-gdal.so (GDAL and PROJ) is missing") != std::string::npos &&
               e.find("/nonexistent/hybridscape-gdal.so (not there)") != std::string::npos &&
               e.find("HS_GDAL_MODULE names it") != std::string::npos;
      };
      // The inverse-distance fill falls back to diffusion, and says so.
      std::vector<float> v = {1, 2, 0, 4};
      FillReport fr;
      const bool filled = fillNodata(v, {1, 1, 0, 1}, 2, 2, NodataFill::InverseDistance, 0.0, fr);
      const bool fellBack = filled && fr.byDiffusion == 1 && v[2] > 1.0f && v[2] < 4.0f &&
                            fr.method.find("inverse distance needs GDAL") != std::string::npos;
      const bool ok = !r.ok() && named(r.error) && r.error.find("grid.asc") != std::string::npos && !s.ok() &&
                      named(s.error) && s.error.find("out.tif") != std::string::npos && fellBack &&
                      !gdal_door::available() && !gdalMapped();
      _exit(ok ? 0 : 1);
    }
    int status = 0;
    QCOMPARE(waitpid(child, &status, 0), child);
    QVERIFY(WIFEXITED(status));
    QCOMPARE(WEXITSTATUS(status), 0);
    QVERIFY(!QFileInfo::exists(QString::fromStdString(path("out.tif"))));
  }

  void gdalIsLoadedOnTheFirstDemOnly() {
    QVERIFY2(!gdalMapped(), "GDAL was mapped before any DEM call");
    DemImportOptions options;
    options.fill = NodataFill::InverseDistance;
    const DemImportResult r = importDem(path("grid.asc"), options);
    QVERIFY2(r.ok(), r.error.c_str());
    QVERIFY(gdalMapped());
    std::string where;
    QVERIFY(gdal_door::available(&where));
    QVERIFY2(where.find("hybridscape-gdal.so") != std::string::npos, where.c_str());

    // The file's heights, row 0 of the terrain being the file's last (south) row.
    const Heightfield& hf = *r.heightfield;
    QCOMPARE(hf.samplesX(), kW);
    QCOMPARE(hf.samplesY(), kH);
    QCOMPARE(r.report.driver, std::string("AAIGrid"));
    QCOMPARE(r.report.spacing.x, 10.0);
    QCOMPARE(r.report.origin.x, 1005.0);  // the south-west pixel's centre
    QCOMPARE(r.report.origin.y, 2005.0);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float expected = kRows[kH - 1 - y][x];
        if (expected == kNodata) continue;
        QCOMPARE(hf.at(x, y), expected);
      }
    // The hole, filled by GDAL's inverse distance from its neighbours (31,
    // 33, 22, 42 and beyond): between the smallest and the largest of them.
    QCOMPARE(r.report.fill.filled, size_t(1));
    QCOMPARE(r.report.fill.byDiffusion, size_t(0));
    const float hole = hf.at(2, 1);
    QVERIFY2(hole > 21.0f && hole < 43.0f, qPrintable(QString::number(hole)));
  }

  void programsDoNotLinkGdal() {
    std::vector<const char*> programs = {"/cli/hybridscape-cli"};
#ifdef HS_EDITOR_BUILT
    programs.push_back("/app/hybridscape");
#endif
    for (const char* program : programs) {
      const QByteArray libs = test::librariesOf(QString(HS_BINARY_DIR) + program);
      QVERIFY2(libs.contains("libc.so"), program);  // the listing worked (and finished)
      QVERIFY2(!libs.contains("libgdal") && !libs.contains("libproj"), program);
    }
  }
};

QTEST_GUILESS_MAIN(TestTerrainGdalDoor)
#include "test_terrain_gdal_door.moc"
