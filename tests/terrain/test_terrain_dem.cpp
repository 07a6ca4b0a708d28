// DEM import/export: true ground size from three CRSs, nodata filling, clear
// errors for bad files, round trips through every export format.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include <OpenImageIO/imageio.h>
#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include "terrain/crs_util.h"
#include "terrain/dem_export.h"
#include "terrain/dem_import.h"
#include "terrain/heightmap_image.h"
#include "terrain/raw_sidecar.h"
#include "terrain/tile_blob.h"
#include "terrain/terrain.h"

using namespace hs::terrain;

namespace {

const std::string kDem = std::string(HS_TEST_DATA_DIR) + "/terrain/dem_wgs84.tif";

// gdalwarp in library form.
bool warp(const std::string& src, const std::string& dst, const std::vector<std::string>& args) {
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  if (!in) return false;
  char** argv = nullptr;
  for (const auto& a : args) argv = CSLAddString(argv, a.c_str());
  GDALWarpAppOptions* o = GDALWarpAppOptionsNew(argv, nullptr);
  CSLDestroy(argv);
  int err = 0;
  GDALDatasetH out = GDALWarp(dst.c_str(), nullptr, 1, &in, o, &err);
  GDALWarpAppOptionsFree(o);
  GDALClose(in);
  if (!out) return false;
  GDALClose(out);
  return true;
}

// Writes a single-band raster (north row first).
bool writeRaster(const std::string& path, const char* driver, int w, int h, const double* gt, const std::string& crs,
                 const std::vector<float>& v, GDALDataType type, const double* nodata) {
  GDALDriverH mem = GDALGetDriverByName("MEM");
  GDALDatasetH ds = GDALCreate(mem, "", w, h, 1, type, nullptr);
  if (!ds) return false;
  if (gt) GDALSetGeoTransform(ds, const_cast<double*>(gt));
  if (!crs.empty()) {
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(s, crs.c_str());
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
  }
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  if (nodata) GDALSetRasterNoDataValue(b, *nodata);
  if (GDALRasterIO(b, GF_Write, 0, 0, w, h, const_cast<float*>(v.data()), w, h, GDT_Float32, 0, 0) != CE_None) return false;
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName(driver), path.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
  GDALClose(ds);
  if (!out) return false;
  GDALClose(out);
  return true;
}

struct DemInfo {
  int w = 0, h = 0;
  double gt[6] = {};
  std::vector<float> v;  // north first
};
DemInfo readDem(const std::string& path) {
  DemInfo d;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  d.w = GDALGetRasterXSize(ds);
  d.h = GDALGetRasterYSize(ds);
  GDALGetGeoTransform(ds, d.gt);
  d.v.resize(size_t(d.w) * size_t(d.h));
  if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, d.w, d.h, d.v.data(), d.w, d.h, GDT_Float32, 0, 0) != CE_None)
    d.v.clear();
  GDALClose(ds);
  return d;
}

bool within(double a, double b, double rel) { return std::abs(a - b) <= rel * std::abs(b); }

// Expects a failed import whose message names the file and contains `what`.
void expectError(const std::string& path, const std::string& what, const DemImportOptions& o = {}) {
  const DemImportResult r = importDem(path, o);
  QVERIFY2(!r.ok(), qPrintable(QString::fromStdString(path + " imported but should not")));
  QVERIFY2(r.error.find(path) != std::string::npos, qPrintable(QString::fromStdString(r.error)));
  QVERIFY2(r.error.find(what) != std::string::npos, qPrintable(QString::fromStdString(r.error)));
  qInfo("%s", r.error.c_str());
}

}  // namespace

class TestDem : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  std::string dir_;
  std::string path(const char* name) const { return dir_ + "/" + name; }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    dir_ = tmp_.path().toStdString();
    GDALAllRegister();
    QVERIFY(QFile::exists(QString::fromStdString(kDem)));
  }

  void sameGroundFromThreeCrs() {
    const DemInfo src = readDem(kDem);
    QCOMPARE(src.w, 367);
    QCOMPARE(src.h, 359);
    // Ground truth: geodesic distances between the first and last pixel
    // centres along the centre parallel and the centre meridian.
    const double lonA = src.gt[0] + 0.5 * src.gt[1], lonB = src.gt[0] + (src.w - 0.5) * src.gt[1];
    const double latA = src.gt[3] + 0.5 * src.gt[5], latB = src.gt[3] + (src.h - 0.5) * src.gt[5];
    const double lonC = 0.5 * (lonA + lonB), latC = 0.5 * (latA + latB);
    const double trueW = geodesicDistance(lonA, latC, lonB, latC), trueH = geodesicDistance(lonC, latA, lonC, latB);
    qInfo("ground truth %.1f x %.1f m", trueW, trueH);

    // UTM fixture: the same ground as an axis-aligned UTM zone 14 raster
    // with the same centre and size (what a survey in UTM delivers).
    SrsPtr wgs = makeSrs("EPSG:4326"), utm = makeSrs("EPSG:32614");
    OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(static_cast<OGRSpatialReferenceH>(wgs.get()),
                                                                     static_cast<OGRSpatialReferenceH>(utm.get()));
    double cx = lonC, cy = latC;
    QVERIFY(OCTTransform(ct, 1, &cx, &cy, nullptr));
    OCTDestroyCoordinateTransformation(ct);
    const double px = trueW / (src.w - 1), py = trueH / (src.h - 1);
    const double hw = 0.5 * px * src.w, hh = 0.5 * py * src.h;
    const std::string utmPath = path("dem_utm14.tif"), merPath = path("dem_3857.tif");
    QVERIFY(warp(kDem, utmPath,
                 {"-t_srs", "EPSG:32614", "-te", std::to_string(cx - hw), std::to_string(cy - hh), std::to_string(cx + hw),
                  std::to_string(cy + hh), "-ts", std::to_string(src.w), std::to_string(src.h), "-r", "bilinear"}));
    QVERIFY(warp(kDem, merPath, {"-t_srs", "EPSG:3857", "-r", "bilinear"}));

    const DemImportResult a = importDem(kDem), b = importDem(utmPath), c = importDem(merPath);
    QVERIFY2(a.ok(), a.error.c_str());
    QVERIFY2(b.ok(), b.error.c_str());
    QVERIFY2(c.ok(), c.error.c_str());
    for (const auto* r : {&a, &b, &c}) qInfo("%s", summary(r->report).c_str());
    QVERIFY(a.report.reprojected);
    QVERIFY(!b.report.reprojected);  // UTM measures ground metres: kept
    QCOMPARE(b.report.targetEpsg, 32614);
    QVERIFY(c.report.reprojected);   // Web Mercator's metres are 19% long at 32.7 N
    QVERIFY(c.report.sourceScaleError > 0.15);
    const glm::dvec2 ga = a.report.groundSize, gb = b.report.groundSize, gc = c.report.groundSize;
    QVERIFY2(within(ga.x, trueW, 0.01) && within(ga.y, trueH, 0.01), "EPSG:4326 import is not at ground size");
    QVERIFY2(within(gb.x, trueW, 0.01) && within(gb.y, trueH, 0.01), "UTM import is not at ground size");
    QVERIFY2(within(gc.x, trueW, 0.01) && within(gc.y, trueH, 0.01), "EPSG:3857 import is not at ground size");
    QVERIFY(within(ga.x, gb.x, 0.01) && within(ga.y, gb.y, 0.01));
    QVERIFY(within(ga.x, gc.x, 0.01) && within(ga.y, gc.y, 0.01));
    // The heights are the same ground too.
    QVERIFY(std::abs(a.report.heightMax - b.report.heightMax) < 10.0f);
    QVERIFY(std::abs(a.report.heightMin - c.report.heightMin) < 10.0f);
    // The CRS travels with the terrain.
    QVERIFY(a.heightfield->geo().valid());
    QVERIFY(b.heightfield->geo().crsWkt.find("UTM zone 14N") != std::string::npos);
    QVERIFY(b.report.fill.filled > 0);  // the UTM raster's corners beyond the source: filled and counted
    // UTM on request: the grid is rotated 0.9 degrees against the DEM's, so
    // the axis-aligned crop is narrower (documented in dem_import.h).
    DemImportOptions o;
    o.crs = DemCrsMode::Utm;
    const DemImportResult u = importDem(kDem, o);
    QVERIFY(u.ok());
    QCOMPARE(u.report.targetEpsg, 32614);
    qInfo("EPSG:4326 -> UTM 14N crop: %.1f x %.1f m (%.2f%% x %.2f%% of ground truth)", u.report.groundSize.x,
          u.report.groundSize.y, 100.0 * u.report.groundSize.x / trueW, 100.0 * u.report.groundSize.y / trueH);
    QVERIFY(within(u.report.groundSize.x, trueW, 0.03));
  }

  void nodataHolesAreFilledAndCounted() {
    DemInfo d = readDem(kDem);
    // A 10 x 10 void and a 3-sample line.
    for (int y = 100; y < 110; ++y)
      for (int x = 200; x < 210; ++x) d.v[size_t(y) * size_t(d.w) + size_t(x)] = -32768.0f;
    for (int x = 50; x < 53; ++x) d.v[size_t(300) * size_t(d.w) + size_t(x)] = -32768.0f;
    const double nd = -32768.0;
    const std::string p = path("holes.tif");
    QVERIFY(writeRaster(p, "GTiff", d.w, d.h, d.gt, "EPSG:4326", d.v, GDT_Int16, &nd));
    // Keep the source grid (no reprojection) to count exactly: a local
    // CRS-less copy would lose the size, so import with KeepSource on a UTM
    // version of the same raster instead.
    const std::string pu = path("holes_utm.tif");
    const double gtU[6] = {500000.0, 30.0, 0.0, 3600000.0, 0.0, -30.0};
    QVERIFY(writeRaster(pu, "GTiff", d.w, d.h, gtU, "EPSG:32614", d.v, GDT_Int16, &nd));
    for (NodataFill method : {NodataFill::Diffusion, NodataFill::InverseDistance}) {
      DemImportOptions o;
      o.fill = method;
      const DemImportResult r = importDem(pu, o);
      QVERIFY2(r.ok(), r.error.c_str());
      QCOMPARE(r.report.fill.filled, size_t(103));
      QCOMPARE(r.report.fill.voids, size_t(2));
      QCOMPARE(r.report.fill.largestVoid, size_t(100));
      QVERIFY(!r.report.warnings.empty());
      qInfo("%s", summary(r.report).c_str());
      // Filled values lie between the rim's extremes (no invented peaks).
      const Heightfield& hf = *r.heightfield;
      float rimLo = 1e9f, rimHi = -1e9f;
      for (int y = 99; y <= 110; ++y)
        for (int x = 199; x <= 210; ++x) {
          const bool rim = y == 99 || y == 110 || x == 199 || x == 210;
          const float v = hf.at(x, d.h - 1 - y);
          QVERIFY(std::isfinite(v));
          if (rim) { rimLo = std::min(rimLo, v); rimHi = std::max(rimHi, v); }
        }
      for (int y = 100; y < 110; ++y)
        for (int x = 200; x < 210; ++x) {
          const float v = hf.at(x, d.h - 1 - y);
          QVERIFY(v >= rimLo - 1e-3f && v <= rimHi + 1e-3f);
        }
    }
    // The geographic version (reprojected) fills too.
    const DemImportResult g = importDem(p);
    QVERIFY(g.ok());
    QVERIFY(g.report.fill.filled > 0);
  }

  void badFilesGiveClearErrors() {
    const double nd = -32768.0;
    const double gt[6] = {500000.0, 30.0, 0.0, 3600000.0, 0.0, -30.0};
    // All nodata.
    const std::string allNd = path("all_nodata.tif");
    QVERIFY(writeRaster(allNd, "GTiff", 20, 20, gt, "EPSG:32614", std::vector<float>(400, -32768.0f), GDT_Int16, &nd));
    expectError(allNd, "nodata");
    // 1 x 1.
    const std::string one = path("one.tif");
    QVERIFY(writeRaster(one, "GTiff", 1, 1, gt, "EPSG:32614", {5.0f}, GDT_Float32, nullptr));
    expectError(one, "1 x 1");
    // Corrupt: a real DEM cut in half, and a file of garbage with a .tif name.
    {
      std::ifstream in(kDem, std::ios::binary);
      std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
      std::ofstream out(path("truncated.tif"), std::ios::binary);
      out.write(bytes.data(), std::streamsize(bytes.size() / 2));
      std::ofstream g(path("garbage.tif"), std::ios::binary);
      for (int i = 0; i < 5000; ++i) g.put(char((i * 7919) & 0xff));
    }
    expectError(path("truncated.tif"), "damaged or truncated");
    expectError(path("garbage.tif"), "not an elevation raster");
    // Not a raster at all.
    {
      std::ofstream t(path("notes.txt"));
      t << "this is not an elevation model\n";
    }
    expectError(path("notes.txt"), "not an elevation raster");
    expectError(path("missing.tif"), "no such file");
    expectError(dir_, "directory");
    // Absurd sizes and windows: a raster that claims 200,000^2 samples.
    {
      GDALDatasetH v = GDALCreate(GDALGetDriverByName("VRT"), path("huge.vrt").c_str(), 200000, 200000, 1, GDT_Float32, nullptr);
      QVERIFY(v);
      double g[6] = {0.0, 1.0, 0.0, 0.0, 0.0, -1.0};
      GDALSetGeoTransform(v, g);
      GDALClose(v);
      expectError(path("huge.vrt"), "import a window");
    }
    DemImportOptions o;
    o.samplesX = 100000;
    o.samplesY = 10;
    expectError(kDem, "outside 2..8193", o);
    o = {};
    o.samplesX = -5;
    expectError(kDem, "outside 2..8193", o);
    o = {};
    o.window.units = DemWindow::Units::Pixels;
    o.window = {DemWindow::Units::Pixels, 1000, 1000, 2000, 2000};
    expectError(kDem, "window", o);
    o.window = {DemWindow::Units::Pixels, 0, 0, NAN, 10};
    expectError(kDem, "non-finite", o);
    o = {};
    o.crs = DemCrsMode::KeepSource;
    expectError(kDem, "degrees", o);
    o.crs = DemCrsMode::Custom;
    o.customCrs = "EPSG:999999";
    expectError(kDem, "not a CRS", o);
    o.band = 3;
    o.crs = DemCrsMode::Auto;
    expectError(kDem, "no band 3", o);
  }

  void exportImportRoundTrips() {
    // A UTM DEM with a real CRS and fractional heights.
    const DemInfo d = readDem(kDem);
    std::vector<float> v = d.v;
    for (size_t i = 0; i < v.size(); ++i) v[i] += float(i % 17) * 0.0173f;
    const double gt[6] = {612345.5, 30.0, 0.0, 3612345.25, 0.0, -30.0};
    const std::string p = path("float_utm.tif");
    QVERIFY(writeRaster(p, "GTiff", d.w, d.h, gt, "EPSG:32614", v, GDT_Float32, nullptr));
    const DemImportResult in = importDem(p);
    QVERIFY2(in.ok(), in.error.c_str());
    const Heightfield& hf = *in.heightfield;
    QCOMPARE(hf.origin().x, 612345.5 + 15.0);
    QCOMPARE(hf.origin().y, 3612345.25 - 30.0 * d.h + 15.0);
    const HeightRange range = hf.range();

    for (const char* name : {"rt.png", "rt.exr", "rt.tif", "rt.r16"}) {
      const std::string out = path(name);
      auto ex = exportHeightmap(hf, out);
      QVERIFY2(ex.ok(), ex.error().c_str());
      Result<Heightfield> back = std::string(name) == "rt.tif"
                                     ? [&]() -> Result<Heightfield> {
                                         DemImportResult r = importDem(out);
                                         if (!r.ok()) return Result<Heightfield>::failure(r.error);
                                         return std::move(*r.heightfield);
                                       }()
                                     : importHeightmap(out);
      QVERIFY2(back.ok(), back.error().c_str());
      QCOMPARE(back->samplesX(), hf.samplesX());
      QCOMPARE(back->samplesY(), hf.samplesY());
      const bool exact = std::string(name) == "rt.exr" || std::string(name) == "rt.tif";
      const double tol = exact ? 0.0 : 0.5 * (double(range.max) - double(range.min)) / 65535.0 + 1e-4;
      double worst = 0.0;
      for (int y = 0; y < hf.samplesY(); ++y)
        for (int x = 0; x < hf.samplesX(); ++x)
          worst = std::max(worst, std::abs(double(back->at(x, y)) - double(hf.at(x, y))));
      qInfo("%s: max height error %.3g m (allowed %.3g)", name, worst, tol);
      QVERIFY(worst <= tol);
      // Placement and CRS survive.
      QVERIFY(std::abs(back->origin().x - hf.origin().x) < 1e-6);
      QVERIFY(std::abs(back->origin().y - hf.origin().y) < 1e-6);
      QVERIFY(std::abs(back->spacing().x - hf.spacing().x) < 1e-9);
      QVERIFY(back->geo().valid());
    }
    // The .r16 sidecar carries what Unreal needs.
    QVERIFY(QFile::exists(QString::fromStdString(path("rt.r16.json"))));
    QVERIFY(!exportHeightmap(hf, path("rt.xyz")).ok());
  }

  void windowsResamplingAndFormats() {
    const double gt[6] = {500000.0, 30.0, 0.0, 3600000.0, 0.0, -30.0};
    DemInfo d = readDem(kDem);
    const std::string p = path("win_utm.tif");
    QVERIFY(writeRaster(p, "GTiff", d.w, d.h, gt, "EPSG:32614", d.v, GDT_Float32, nullptr));
    const DemImportResult full = importDem(p);
    QVERIFY(full.ok());
    // Pixel window: same heights as the full import.
    DemImportOptions o;
    o.window = {DemWindow::Units::Pixels, 100, 50, 200, 150};
    const DemImportResult w = importDem(p, o);
    QVERIFY2(w.ok(), w.error.c_str());
    QCOMPARE(w.heightfield->samplesX(), 100);
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 100; ++x)
        QCOMPARE(w.heightfield->at(x, y), full.heightfield->at(100 + x, (d.h - 150) + y));
    // Map-coordinate window.
    o.window = {DemWindow::Units::SourceCrs, 503000.0, 3592000.0, 506000.0, 3595000.0};
    const DemImportResult wm = importDem(p, o);
    QVERIFY2(wm.ok(), wm.error.c_str());
    QCOMPARE(wm.heightfield->samplesX(), 100);
    // Lon/lat window on the geographic DEM.
    o.window = {DemWindow::Units::LonLat, -97.45, 32.6, -97.35, 32.7};
    const DemImportResult wl = importDem(kDem, o);
    QVERIFY2(wl.ok(), wl.error.c_str());
    QVERIFY(within(wl.report.groundSize.x, geodesicDistance(-97.45, 32.65, -97.35, 32.65), 0.03));

    // Resampled to a CDLOD-friendly size: same ground, corners kept.
    for (Resampling m : {Resampling::Bilinear, Resampling::Cubic, Resampling::Nearest}) {
      DemImportOptions r;
      r.samplesX = r.samplesY = 257;
      r.resampling = m;
      const DemImportResult rs = importDem(p, r);
      QVERIFY(rs.ok());
      QVERIFY(within(rs.report.groundSize.x, full.report.groundSize.x, 1e-12));
      QCOMPARE(rs.heightfield->at(0, 0), full.heightfield->at(0, 0));
      QCOMPARE(rs.heightfield->at(256, 256), full.heightfield->at(d.w - 1, d.h - 1));
    }

    // ASCII grid with a nodata value, no CRS: cell size taken as metres.
    {
      std::ofstream a(path("grid.asc"));
      a << "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n"
        << "1 2 3 4\n5 -9999 7 8\n9 10 11 12\n";
    }
    const DemImportResult asc = importDem(path("grid.asc"));
    QVERIFY2(asc.ok(), asc.error.c_str());
    QCOMPARE(asc.report.fill.filled, size_t(1));
    QCOMPARE(asc.heightfield->at(0, 0), 9.0f);  // south-west
    QCOMPARE(asc.heightfield->at(3, 2), 4.0f);  // north-east
    QCOMPARE(asc.report.groundSize.x, 30.0);
    QCOMPARE(asc.heightfield->origin().x, 1005.0);
    QVERIFY(std::abs(asc.heightfield->at(1, 1) - 6.5f) < 0.75f);  // filled from its neighbours

    // SRTM .hgt (1 arc-second tile N32W098, 3601^2) and DTED level 0.
    {
      std::vector<float> hgt(size_t(3601) * 3601);
      for (int y = 0; y < 3601; ++y)
        for (int x = 0; x < 3601; ++x) hgt[size_t(y) * 3601 + size_t(x)] = float(200 + (x + y) % 50);
      const double g[6] = {-98.0 - 0.5 / 3600.0, 1.0 / 3600.0, 0.0, 33.0 + 0.5 / 3600.0, 0.0, -1.0 / 3600.0};
      QVERIFY(writeRaster(path("N32W098.hgt"), "SRTMHGT", 3601, 3601, g, "EPSG:4326", hgt, GDT_Int16, nullptr));
      DemImportOptions s;
      s.window = {DemWindow::Units::LonLat, -97.6, 32.5, -97.5, 32.6};
      const DemImportResult srtm = importDem(path("N32W098.hgt"), s);
      QVERIFY2(srtm.ok(), srtm.error.c_str());
      QCOMPARE(srtm.report.driver, std::string("SRTMHGT"));
      QVERIFY(within(srtm.report.groundSize.y, geodesicDistance(-97.55, 32.5, -97.55, 32.6), 0.02));
      std::vector<float> dt(121 * 121, 300.0f);
      const double gd[6] = {-98.0 - 0.5 / 120.0, 1.0 / 120.0, 0.0, 33.0 + 0.5 / 120.0, 0.0, -1.0 / 120.0};
      QVERIFY(writeRaster(path("w098_n32.dt0"), "DTED", 121, 121, gd, "EPSG:4326", dt, GDT_Int16, nullptr));
      const DemImportResult dted = importDem(path("w098_n32.dt0"));
      QVERIFY2(dted.ok(), dted.error.c_str());
      QCOMPARE(dted.report.driver, std::string("DTED"));
      QVERIFY(std::abs(dted.report.heightMax - 300.0f) < 1e-3f);
    }
  }

  // The .r16 sidecar (terrain/raw_sidecar.h) reads back what was written,
  // exactly; one that is damaged is refused naming the file and the place
  // (it was taken as "no sidecar" and the size guessed).
  void rawSidecar() {
    auto t = Terrain::create(HeightfieldDesc{65, 33, {64.0, 32.0}, {512345.123456789, 4412345.987654321, 0.1}, 0.0f, {}});
    QVERIFY(t.ok());
    for (int y = 0; y < 33; ++y)
      for (int x = 0; x < 65; ++x) t->height.set(x, y, float(x) * 0.37f + float(y) * 1.1f);
    const std::string r16 = path("side.r16"), side = r16 + ".json";
    auto ex = exportHeightmap(t->height, r16);
    QVERIFY2(ex.ok(), ex.error().c_str());
    QCOMPARE(ex->sidecar, side);
    std::string error;
    const std::optional<RawSidecar> s = readRawSidecar(side, error);
    QVERIFY2(s, error.c_str());
    QCOMPARE(s->width, 65);
    QCOMPARE(s->height, 33);
    QCOMPARE(s->origin, t->height.origin());  // the doubles themselves
    QCOMPARE(s->spacing, t->height.spacing());
    QCOMPARE(s->heightMin, double(ex->range.min));
    QCOMPARE(s->heightMax, double(ex->range.max));

    std::stringstream written;
    written << std::ifstream(side).rdbuf();
    const std::string good = written.str();
    auto refused = [&](const std::string& text, const std::string& what) {
      std::ofstream(side, std::ios::trunc) << text;
      Result<Heightfield> back = importHeightmap(r16);
      QVERIFY(!back.ok());
      QVERIFY2(back.error().find(side) != std::string::npos && back.error().find(what) != std::string::npos,
               back.error().c_str());
    };
    std::string wrong = good;
    const size_t w = wrong.find("\"width\": 65");
    QVERIFY(w != std::string::npos);
    wrong.replace(w, std::string("\"width\": 65").size(), "\"width\": \"65\"");
    refused(wrong, "width (line 5, column 12): expected a whole number");
    refused(good.substr(0, good.size() / 2), "not a JSON sidecar (line ");
    refused("{\"width\": 65, \"width\": 66, \"height\": 33}", "duplicate key \"width\"");
    refused("{\"height\": 33}", "width: missing");
    // As written, it reads.
    std::ofstream(side, std::ios::trunc) << good;
    QVERIFY(importHeightmap(r16).ok());
  }

  void paintWeightsAsImages() {
    auto t = Terrain::create(HeightfieldDesc{64, 32, {63.0, 31.0}, {}, 0.0f, {}});
    QVERIFY(t.ok());
    for (int x = 0; x < 32; ++x) t->paint.blend(x, 0, 2, 1.0f);  // south row, west half: layer 2
    QVERIFY(exportPaintLayerImage(t->paint, 2, path("layer2.png"), 16).ok());
    QVERIFY(exportSplatMap(t->paint, 0, path("splat.png")).ok());
    QVERIFY(!exportPaintLayerImage(t->paint, 20, path("bad.png")).ok());
    auto in = OIIO::ImageInput::open(path("layer2.png"));
    QVERIFY(in);
    std::vector<float> px(64 * 32);
    QVERIFY(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, px.data()));
    QCOMPARE(px[31 * 64 + 0], 1.0f);   // image row 31 = south
    QCOMPARE(px[31 * 64 + 40], 0.0f);
    QCOMPARE(px[0], 0.0f);
    // The alpha channel is layer 3's weight, not coverage: read it unassociated.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto sp = OIIO::ImageInput::open(path("splat.png"), &config);
    QVERIFY(sp);
    QCOMPARE(sp->spec().nchannels, 4);
    std::vector<uint8_t> rgba(64 * 32 * 4);
    QVERIFY(sp->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, rgba.data()));
    QCOMPARE(int(rgba[(31 * 64 + 0) * 4 + 2]), 255);  // layer 2 in blue
    QCOMPARE(int(rgba[(31 * 64 + 40) * 4 + 0]), 255); // layer 0 in red
  }

  // Tile blobs are deflated with libdeflate since GDAL left hs_terrain
  // (gdal_door.h); before, GDAL's CPLZLibDeflate wrote them. The streams
  // must be GDAL's byte for byte (so that a saved terrain's blobs, and the
  // hashes of them, do not change) and GDAL must read them.
  void tileBlobsAreTheBytesGdalWrote() {
    auto t = Terrain::create(HeightfieldDesc{260, 140, {259.0, 139.0}, {}, 0.0f, {}});
    QVERIFY(t.ok());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> noise(0.f, 2.f);
    for (int y = 0; y < 140; ++y)
      for (int x = 0; x < 260; ++x)
        t->height.heights().set(x, y, 300.0f + 20.0f * std::sin(x * 0.05f) * std::cos(y * 0.07f) + noise(rng));
    int deflated = 0;
    for (int tile = 0; tile < t->height.heights().tileCount(); ++tile) {
      const std::vector<uint8_t> blob = encodeHeightTile(t->height, tile);
      constexpr size_t kHeader = 32, kFlags = 7, kPayloadBytes = 20;
      QVERIFY(blob.size() > kHeader);
      if (!(blob[kFlags] & 2)) continue;  // not deflated
      ++deflated;
      uint32_t n = 0;
      std::memcpy(&n, &blob[kPayloadBytes], 4);
      QCOMPARE(size_t(n), blob.size() - kHeader);
      std::vector<uint8_t> planes(TileGrid<float>::tileBytes()), again(planes.size() + 1024);
      size_t got = 0, redone = 0;
      QVERIFY(CPLZLibInflate(&blob[kHeader], n, planes.data(), planes.size(), &got));
      QCOMPARE(got, planes.size());
      QVERIFY(CPLZLibDeflate(planes.data(), planes.size(), 6, again.data(), again.size(), &redone));
      again.resize(redone);
      QVERIFY(std::equal(again.begin(), again.end(), blob.begin() + long(kHeader), blob.end()));
    }
    QVERIFY(deflated >= 4);
  }

  void cancelledImport() {
    hs::Progress p;
    p.cancel();
    const DemImportResult r = importDem(kDem, {}, &p);
    QVERIFY(!r.ok());
    QVERIFY(r.cancelled);
  }
};

QTEST_GUILESS_MAIN(TestDem)
#include "test_terrain_dem.moc"
