// The GDAL side of a DEM import (terrain/gdal_door.h): opening the file,
// the window, the target CRS, reading and reprojecting, vertical units.
// Built into the GDAL module, hybridscape-gdal.so, not into hs_terrain; the
// rest of the import (nodata fill, resizing, the heightfield) is
// dem_import.cpp's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <cpl_string.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include "terrain/crs_util.h"
#include "terrain/gdal_side.h"
#include "terrain/gdal_util.h"

namespace hs::terrain {
namespace {

struct Fail {
  std::string msg;
};

// Disagreement above this between a CRS's distances and ground distances
// means the CRS cannot give the terrain its true size.
constexpr double kMaxScaleError = 0.005;

struct GdalProgressData {
  const Progress* progress;
  double base, span;
  const char* stage;
};
int gdalProgress(double complete, const char*, void* data) {
  auto* d = static_cast<GdalProgressData*>(data);
  if (!d || !d->progress) return TRUE;
  d->progress->report(d->base + d->span * complete, d->stage);
  return d->progress->cancelled() ? FALSE : TRUE;
}

// Pixel (col,row) -> georeferenced coordinates.
glm::dvec2 applyGt(const double* gt, double col, double row) {
  return {gt[0] + col * gt[1] + row * gt[2], gt[3] + col * gt[4] + row * gt[5]};
}

// |CRS distance / geodesic distance - 1| across the window (left-right and
// top-bottom through the centre).
double measureScaleError(OGRSpatialReferenceH srs, const double* gt, int x0, int y0, int w, int h,
                         double unitToMetre) {
  SrsPtr geog(OSRCloneGeogCS(srs));
  if (!geog) return 0.0;
  OSRSetAxisMappingStrategy(static_cast<OGRSpatialReferenceH>(geog.get()), OAMS_TRADITIONAL_GIS_ORDER);
  TransformPtr ct = makeTransform(srs, static_cast<OGRSpatialReferenceH>(geog.get()));
  if (!ct) return 0.0;
  double worst = 0.0;
  const double cx = x0 + 0.5 * w, cy = y0 + 0.5 * h;
  const glm::dvec2 ends[2][2] = {{applyGt(gt, x0, cy), applyGt(gt, x0 + w, cy)},
                                 {applyGt(gt, cx, y0), applyGt(gt, cx, y0 + h)}};
  for (const auto& e : ends) {
    double xs[2] = {e[0].x, e[1].x}, ys[2] = {e[0].y, e[1].y};
    const double planar = glm::length(e[1] - e[0]) * unitToMetre;
    if (!OCTTransform(static_cast<OGRCoordinateTransformationH>(ct.get()), 2, xs, ys, nullptr)) continue;
    const double ground = geodesicDistance(xs[0], ys[0], xs[1], ys[1]);
    if (ground > 0.0) worst = std::max(worst, std::abs(planar / ground - 1.0));
  }
  return worst;
}

// The largest axis-aligned rectangle (in `to`) inside the footprint of the
// pixel window (in `from`), from densified edges.
bool innerRectangle(OGRSpatialReferenceH from, OGRSpatialReferenceH to, const double* gt, int x0, int y0, int w,
                    int h, double& xmin, double& ymin, double& xmax, double& ymax, std::string& err) {
  TransformPtr ct = makeTransform(from, to);
  if (!ct) {
    err = "no coordinate transformation between the DEM's CRS and the target CRS";
    return false;
  }
  constexpr int N = 64;
  std::vector<double> ex[4], ey[4];  // edges: col=x0, col=x0+w, row=y0, row=y0+h
  for (int e = 0; e < 4; ++e) {
    for (int i = 0; i <= N; ++i) {
      const double t = double(i) / N;
      const double col = e == 0 ? x0 : e == 1 ? x0 + w : x0 + t * w;
      const double row = e == 2 ? y0 : e == 3 ? y0 + h : y0 + t * h;
      const glm::dvec2 p = applyGt(gt, col, row);
      ex[e].push_back(p.x);
      ey[e].push_back(p.y);
    }
    std::vector<int> ok(ex[e].size());
    if (!OCTTransformEx(static_cast<OGRCoordinateTransformationH>(ct.get()), int(ex[e].size()), ex[e].data(),
                        ey[e].data(), nullptr, ok.data()) ||
        std::find(ok.begin(), ok.end(), 0) != ok.end()) {
      err = "the DEM's footprint cannot be transformed to the target CRS (outside its area of use?)";
      return false;
    }
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double d : v) s += d;
    return s / double(v.size());
  };
  // Which column edge is west, which row edge is south (any geotransform sign).
  const int west = mean(ex[0]) < mean(ex[1]) ? 0 : 1, east = 1 - west;
  const int south = mean(ey[2]) < mean(ey[3]) ? 2 : 3, north = 5 - south;
  xmin = *std::max_element(ex[west].begin(), ex[west].end());
  xmax = *std::min_element(ex[east].begin(), ex[east].end());
  ymin = *std::max_element(ey[south].begin(), ey[south].end());
  ymax = *std::min_element(ey[north].begin(), ey[north].end());
  if (!(xmax > xmin && ymax > ymin)) {
    err = "the DEM's footprint is degenerate in the target CRS";
    return false;
  }
  return true;
}

// Transverse Mercator centred on (lon, lat) on the DEM's own datum, scale 1,
// origin at the centre. Centre rounded to 1e-4 degrees (about 10 m) so the
// definition reads well and repeats for the same DEM.
SrsPtr localTransverseMercator(OGRSpatialReferenceH geog, double lon, double lat) {
  const double lon0 = std::round(lon * 1e4) / 1e4, lat0 = std::round(lat * 1e4) / 1e4;
  SrsPtr t = cloneSrs(geog);
  if (!t) return nullptr;
  OGRSpatialReferenceH h = static_cast<OGRSpatialReferenceH>(t.get());
  char name[128];
  std::snprintf(name, sizeof name, "Local transverse Mercator %.4f %s %.4f %s", std::abs(lat0), lat0 >= 0 ? "N" : "S",
                std::abs(lon0), lon0 >= 0 ? "E" : "W");
  if (OSRSetProjCS(h, name) != OGRERR_NONE || OSRSetTM(h, lat0, lon0, 1.0, 0.0, 0.0) != OGRERR_NONE ||
      OSRSetLinearUnits(h, SRS_UL_METER, 1.0) != OGRERR_NONE)
    return makeSrs("+proj=tmerc +lat_0=" + std::to_string(lat0) + " +lon_0=" + std::to_string(lon0) +
                   " +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs");
  OSRSetAxisMappingStrategy(h, OAMS_TRADITIONAL_GIS_ORDER);
  return t;
}

char** toArgv(const std::vector<std::string>& args) {
  char** argv = nullptr;
  for (const auto& a : args) argv = CSLAddString(argv, a.c_str());
  return argv;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

const char* gdalResampling(Resampling r) {
  switch (r) {
    case Resampling::Nearest: return "near";
    case Resampling::Cubic: return "cubic";
    default: return "bilinear";
  }
}

double verticalUnitScale(const char* unit, std::string& name) {
  std::string u = unit ? unit : "";
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  name = u.empty() ? "m (assumed)" : u;
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
  if (u == "us survey foot" || u == "us-ft" || u == "ftus") return 1200.0 / 3937.0;
  if (u == "cm" || u == "centimetre" || u == "centimeter") return 0.01;
  return 1.0;
}

// Throws Fail; `cancelled` is set when it stops for a Cancel.
void read(const std::string& path, const DemImportOptions& opt, const Progress* progress, gdal_door::DemRaster& out,
          DemImportReport& rep, bool& cancelled) {
  auto fail = [&](const std::string& m) { throw Fail{path + ": " + m}; };

  ensureGdalRegistered();
  GdalErrorCapture gdalErrors;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("no such file");
  if (std::filesystem::is_directory(path, ec)) fail("is a directory, not an elevation file");
  if (opt.samplesX < 0 || opt.samplesY < 0 || opt.samplesX == 1 || opt.samplesY == 1 || opt.samplesX > kMaxSamples ||
      opt.samplesY > kMaxSamples)
    fail("requested terrain size " + std::to_string(opt.samplesX) + " x " + std::to_string(opt.samplesY) +
         " is outside 2..8193 samples per side (0 = the DEM's own)");

  DatasetPtr ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr,
                           nullptr, nullptr));
  if (!ds) {
    const std::string why = gdalErrors.lastError();
    fail("not an elevation raster GDAL can read" + (why.empty() ? std::string() : " (" + why + ")") +
         "; expected GeoTIFF, DTED, SRTM .hgt, ASCII grid or another GDAL raster");
  }
  GDALDriverH drv = GDALGetDatasetDriver(ds.get());
  rep.driver = drv ? GDALGetDriverShortName(drv) : "?";
  // A text grid cut in its last line still reads: GDAL takes `12.2` for a
  // cut `12.25` and missing values for nodata (which are then filled). A
  // missing final line end is said, never silent.
  if (rep.driver == "AAIGrid" || rep.driver == "GRASSASCIIGrid" || rep.driver == "XYZ") {
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
      const bool cut = std::fseek(f, -1, SEEK_END) == 0 && std::fgetc(f) != '\n';
      std::fclose(f);
      if (cut)
        rep.warnings.push_back("the file does not end with a line end, so it may have been cut short; its last "
                               "line was read as it stands (a value cut short, or missing and filled as nodata)");
    }
  }
  const int W = GDALGetRasterXSize(ds.get()), H = GDALGetRasterYSize(ds.get());
  rep.sourceWidth = W;
  rep.sourceHeight = H;
  if (GDALGetRasterCount(ds.get()) < 1) fail("has no raster band");
  if (opt.band < 1 || opt.band > GDALGetRasterCount(ds.get()))
    fail("has no band " + std::to_string(opt.band) + " (it has " + std::to_string(GDALGetRasterCount(ds.get())) + ")");
  if (W < 2 || H < 2)
    fail("is " + std::to_string(W) + " x " + std::to_string(H) +
         " samples; a terrain needs at least 2 x 2 (a single elevation has no extent)");
  GDALRasterBandH band = GDALGetRasterBand(ds.get(), opt.band);
  if (GDALDataTypeIsComplex(GDALGetRasterDataType(band))) fail("has complex-valued samples, not elevations");

  double gt[6] = {0, 1, 0, 0, 0, 1};
  const bool hasGt = GDALGetGeoTransform(ds.get(), gt) == CE_None;
  const bool rotated = hasGt && (gt[2] != 0.0 || gt[4] != 0.0);
  if (hasGt && !(std::isfinite(gt[1]) && std::isfinite(gt[5]) && gt[1] != 0.0 && gt[5] != 0.0))
    fail("has an invalid geotransform (pixel size " + fmt(gt[1]) + " x " + fmt(gt[5]) + ")");
  OGRSpatialReferenceH srcSrsRaw = GDALGetSpatialRef(ds.get());
  SrsPtr srcSrs = cloneSrs(srcSrsRaw);
  OGRSpatialReferenceH src = static_cast<OGRSpatialReferenceH>(srcSrs.get());
  rep.sourceCrs = src ? srsName(src) : "none";
  rep.sourceEpsg = srsEpsg(src);
  if (!hasGt)
    rep.warnings.push_back("no georeferencing: pixels taken as " + fmt(opt.assumedCellSize) + " m");

  // --- window in source pixels -----------------------------------------
  int wx0 = 0, wy0 = 0, wx1 = W, wy1 = H;
  const DemWindow& win = opt.window;
  if (win.units != DemWindow::Units::Full) {
    if (!(std::isfinite(win.minX) && std::isfinite(win.minY) && std::isfinite(win.maxX) && std::isfinite(win.maxY)))
      fail("the import window has a non-finite coordinate");
    double px0, py0, px1, py1;
    if (win.units == DemWindow::Units::Pixels) {
      px0 = win.minX; py0 = win.minY; px1 = win.maxX; py1 = win.maxY;
    } else {
      if (!hasGt || rotated) fail("a window in map coordinates needs a north-up georeferenced DEM");
      double bx0 = win.minX, by0 = win.minY, bx1 = win.maxX, by1 = win.maxY;
      if (win.units == DemWindow::Units::LonLat) {
        if (!src) fail("a window in degrees needs a DEM with a CRS");
        SrsPtr wgs = makeSrs("EPSG:4326");
        TransformPtr ct = makeTransform(static_cast<OGRSpatialReferenceH>(wgs.get()), src);
        if (!ct) fail("cannot transform the lon/lat window to the DEM's CRS");
        std::vector<double> xs, ys;
        for (int i = 0; i <= 16; ++i) {
          const double t = i / 16.0;
          for (auto [x, y] : {std::pair{bx0 + t * (bx1 - bx0), by0}, std::pair{bx0 + t * (bx1 - bx0), by1},
                              std::pair{bx0, by0 + t * (by1 - by0)}, std::pair{bx1, by0 + t * (by1 - by0)}}) {
            xs.push_back(x);
            ys.push_back(y);
          }
        }
        if (!OCTTransform(static_cast<OGRCoordinateTransformationH>(ct.get()), int(xs.size()), xs.data(), ys.data(),
                          nullptr))
          fail("cannot transform the lon/lat window to the DEM's CRS");
        bx0 = *std::min_element(xs.begin(), xs.end());
        bx1 = *std::max_element(xs.begin(), xs.end());
        by0 = *std::min_element(ys.begin(), ys.end());
        by1 = *std::max_element(ys.begin(), ys.end());
      }
      const double c0 = (bx0 - gt[0]) / gt[1], c1 = (bx1 - gt[0]) / gt[1];
      const double r0 = (by0 - gt[3]) / gt[5], r1 = (by1 - gt[3]) / gt[5];
      px0 = std::min(c0, c1); px1 = std::max(c0, c1); py0 = std::min(r0, r1); py1 = std::max(r0, r1);
    }
    wx0 = int(std::clamp(std::floor(px0), 0.0, double(W)));
    wy0 = int(std::clamp(std::floor(py0), 0.0, double(H)));
    wx1 = int(std::clamp(std::ceil(px1), 0.0, double(W)));
    wy1 = int(std::clamp(std::ceil(py1), 0.0, double(H)));
    if (wx1 - wx0 < 2 || wy1 - wy0 < 2)
      fail("the import window covers " + std::to_string(std::max(0, wx1 - wx0)) + " x " +
           std::to_string(std::max(0, wy1 - wy0)) + " samples of the DEM; it needs at least 2 x 2 inside the file");
  }
  const int ww = wx1 - wx0, wh = wy1 - wy0;
  rep.windowX = wx0; rep.windowY = wy0; rep.windowW = ww; rep.windowH = wh;
  // Reading more than this without overviews takes hours: ask for a window.
  constexpr double kMaxSourceSamples = 4e9;
  if (double(ww) * double(wh) > kMaxSourceSamples && GDALGetOverviewCount(band) == 0)
    fail("the area to import is " + std::to_string(ww) + " x " + std::to_string(wh) + " samples (" +
         fmt(std::round(double(ww) * double(wh) / 1e8) / 10.0) +
         " billion) with no overviews; import a window of it, or build overviews (gdaladdo) first");

  // --- target CRS --------------------------------------------------------
  double unitToMetre = 1.0;
  const bool geographic = src && OSRIsGeographic(src);
  if (src && OSRIsProjected(src)) unitToMetre = OSRGetLinearUnits(src, nullptr);
  if (src && hasGt && !geographic) rep.sourceScaleError = measureScaleError(src, gt, wx0, wy0, ww, wh, unitToMetre);
  SrsPtr target;
  switch (opt.crs) {
    case DemCrsMode::KeepSource:
      if (geographic)
        fail("its CRS (" + rep.sourceCrs + ") is in degrees; keeping it would give a terrain no size in metres. "
             "Import with automatic or UTM reprojection");
      if (src && std::abs(unitToMetre - 1.0) > 1e-9)
        fail("its CRS (" + rep.sourceCrs + ") measures in units of " + fmt(unitToMetre) +
             " m, not metres; import with automatic reprojection");
      if (rep.sourceScaleError > kMaxScaleError)
        rep.warnings.push_back("kept " + rep.sourceCrs + " although its distances differ from the ground by " +
                               fmt(std::round(rep.sourceScaleError * 1e4) / 100.0) + "%");
      break;
    case DemCrsMode::Custom: {
      target = makeSrs(opt.customCrs);
      if (!target) fail("the target CRS '" + opt.customCrs + "' is not a CRS GDAL knows");
      if (OSRIsGeographic(static_cast<OGRSpatialReferenceH>(target.get())))
        fail("the target CRS '" + opt.customCrs + "' is in degrees; a terrain needs a projected (metric) CRS");
      break;
    }
    case DemCrsMode::LocalTransverseMercator:
    case DemCrsMode::Utm:
    case DemCrsMode::Auto: {
      const bool needs = opt.crs != DemCrsMode::Auto || geographic || (src && std::abs(unitToMetre - 1.0) > 1e-9) ||
                         rep.sourceScaleError > kMaxScaleError;
      if (needs) {
        if (!src || !hasGt) fail("has no CRS to reproject from");
        // Centre of the window in lon/lat.
        SrsPtr geog(OSRCloneGeogCS(src));
        OSRSetAxisMappingStrategy(static_cast<OGRSpatialReferenceH>(geog.get()), OAMS_TRADITIONAL_GIS_ORDER);
        TransformPtr ct = makeTransform(src, static_cast<OGRSpatialReferenceH>(geog.get()));
        glm::dvec2 c = applyGt(gt, wx0 + 0.5 * ww, wy0 + 0.5 * wh);
        if (!ct || !OCTTransform(static_cast<OGRCoordinateTransformationH>(ct.get()), 1, &c.x, &c.y, nullptr))
          fail("cannot find the DEM's centre in longitude/latitude");
        if (opt.crs == DemCrsMode::Utm && std::abs(c.y) <= 84.0) {
          target = makeSrs("EPSG:" + std::to_string(utmEpsgFor(c.x, c.y)));
        } else {
          target = localTransverseMercator(static_cast<OGRSpatialReferenceH>(geog.get()), c.x, c.y);
        }
        if (!target) fail("cannot create the local metric CRS");
        if (geographic || unitToMetre != 1.0 || rep.sourceScaleError > kMaxScaleError)
          rep.warnings.push_back("reprojected from " + rep.sourceCrs + " to " +
                                 srsName(static_cast<OGRSpatialReferenceH>(target.get())) +
                                 " so the terrain has its true ground size");
      }
      break;
    }
  }
  OGRSpatialReferenceH tgt = static_cast<OGRSpatialReferenceH>(target.get());
  rep.reprojected = tgt != nullptr;

  // --- read ----------------------------------------------------------------
  int gw = 0, gh = 0;                 // grid read (north row first)
  std::vector<float> values;
  std::vector<uint8_t> valid;
  double px = 1.0, py = 1.0;          // pixel size in metres (target CRS units)
  glm::dvec2 sw{0.0};                 // south-west pixel centre
  std::string outWkt;
  int noData = 0;
  double nd = GDALGetRasterNoDataValue(band, &noData);
  if (opt.nodataValue) {
    nd = *opt.nodataValue;
    noData = 1;
  }
  rep.hasNodata = noData != 0;
  rep.nodataValue = nd;
  const bool bigWindow = ww > kMaxSamples || wh > kMaxSamples;
  GdalProgressData pd{progress, 0.0, 0.6, "reading elevation"};

  if (tgt || bigWindow || rotated) {
    // Through GDALWarp (reprojection, de-rotation, or reduction of a window
    // larger than a terrain can be; nodata is honoured by the warper).
    std::vector<std::string> trArgs = {"-of", "VRT", "-b", std::to_string(opt.band), "-srcwin", std::to_string(wx0),
                                       std::to_string(wy0), std::to_string(ww), std::to_string(wh)};
    if (noData) trArgs.insert(trArgs.end(), {"-a_nodata", fmt(nd)});
    char** trArgv = toArgv(trArgs);
    GDALTranslateOptions* to = GDALTranslateOptionsNew(trArgv, nullptr);
    CSLDestroy(trArgv);
    DatasetPtr sub(GDALTranslate("", ds.get(), to, nullptr));
    GDALTranslateOptionsFree(to);
    if (!sub) fail("cannot read the window (" + gdalErrors.lastError() + ")");

    std::vector<std::string> args = {"-of", "MEM", "-ot", "Float32", "-r", gdalResampling(opt.resampling),
                                     "-dstnodata", "nan"};
    OGRSpatialReferenceH outSrs = tgt ? tgt : src;
    double xmin, ymin, xmax, ymax;
    if (outSrs && src) {
      std::string err;
      if (!innerRectangle(src, outSrs, gt, wx0, wy0, ww, wh, xmin, ymin, xmax, ymax, err)) fail(err);
      args.insert(args.end(), {"-t_srs", srsWkt(outSrs)});
    } else {
      // No CRS (rotated or huge local grid): stay in the file's coordinates.
      const glm::dvec2 a = applyGt(gt, wx0, wy0), b = applyGt(gt, wx1, wy1);
      xmin = std::min(a.x, b.x); xmax = std::max(a.x, b.x); ymin = std::min(a.y, b.y); ymax = std::max(a.y, b.y);
    }
    // About the source's number of pixels, square, at most 8193 per side.
    double p = std::sqrt((xmax - xmin) * (ymax - ymin) / (double(ww) * double(wh)));
    p = std::max({p, (xmax - xmin) / kMaxSamples, (ymax - ymin) / kMaxSamples});
    gw = std::clamp(int(std::lround((xmax - xmin) / p)), 2, kMaxSamples);
    gh = std::clamp(int(std::lround((ymax - ymin) / p)), 2, kMaxSamples);
    args.insert(args.end(), {"-te", fmt(xmin), fmt(ymin), fmt(xmax), fmt(ymax), "-ts", std::to_string(gw),
                             std::to_string(gh)});
    char** argv = toArgv(args);
    GDALWarpAppOptions* wo = GDALWarpAppOptionsNew(argv, nullptr);
    CSLDestroy(argv);
    GDALWarpAppOptionsSetProgress(wo, gdalProgress, &pd);
    GDALDatasetH srcH = sub.get();
    int usageError = 0;
    DatasetPtr warped(GDALWarp("", nullptr, 1, &srcH, wo, &usageError));
    GDALWarpAppOptionsFree(wo);
    if (isCancelled(progress)) {
      cancelled = true;
      throw Fail{path + ": import cancelled"};
    }
    if (!warped)
      fail("cannot read or reproject the elevations; the file may be damaged or truncated (" + gdalErrors.lastError() +
           ")");
    values.resize(size_t(gw) * size_t(gh));
    if (GDALRasterIO(GDALGetRasterBand(warped.get(), 1), GF_Read, 0, 0, gw, gh, values.data(), gw, gh, GDT_Float32, 0,
                     0) != CE_None)
      fail("cannot read the reprojected elevations; the file may be damaged or truncated (" + gdalErrors.lastError() + ")");
    valid = std::vector<uint8_t>(values.size());
    for (size_t i = 0; i < values.size(); ++i) valid[i] = std::isfinite(values[i]) ? 1 : 0;
    px = (xmax - xmin) / gw;
    py = (ymax - ymin) / gh;
    sw = {xmin + 0.5 * px, ymin + 0.5 * py};
    if (outSrs) outWkt = srsWkt(outSrs);
    if (outSrs && !tgt) rep.warnings.push_back("window resampled to " + std::to_string(gw) + " x " + std::to_string(gh) +
                                               " (a terrain has at most 8193 samples per side)");
  } else {
    gw = ww;
    gh = wh;
    values.resize(size_t(gw) * size_t(gh));
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.pfnProgress = gdalProgress;
    extra.pProgressData = &pd;
    if (GDALRasterIOEx(band, GF_Read, wx0, wy0, ww, wh, values.data(), gw, gh, GDT_Float32, 0, 0, &extra) != CE_None) {
      if (isCancelled(progress)) {
        cancelled = true;
        throw Fail{path + ": import cancelled"};
      }
      fail("cannot read the elevations; the file is damaged or truncated (" + gdalErrors.lastError() + ")");
    }
    valid = std::vector<uint8_t>(values.size());
    const float ndf = float(nd);
    for (size_t i = 0; i < values.size(); ++i)
      valid[i] = std::isfinite(values[i]) && !(noData && (values[i] == ndf || double(values[i]) == nd)) ? 1 : 0;
    if (hasGt) {
      px = std::abs(gt[1]) * unitToMetre;
      py = std::abs(gt[5]) * unitToMetre;
      // Centre of the south-west pixel of the window.
      const double col = gt[1] > 0 ? wx0 + 0.5 : wx1 - 0.5;
      const double row = gt[5] < 0 ? wy1 - 0.5 : wy0 + 0.5;
      sw = applyGt(gt, col, row) * unitToMetre;
      // Rows must run north first, columns west first.
      if (gt[5] > 0)
        for (int y = 0; y < gh / 2; ++y)
          for (int x = 0; x < gw; ++x) {
            std::swap(values[size_t(y) * size_t(gw) + size_t(x)], values[size_t(gh - 1 - y) * size_t(gw) + size_t(x)]);
            std::swap(valid[size_t(y) * size_t(gw) + size_t(x)], valid[size_t(gh - 1 - y) * size_t(gw) + size_t(x)]);
          }
      if (gt[1] < 0)
        for (int y = 0; y < gh; ++y) {
          std::reverse(values.begin() + long(y) * gw, values.begin() + long(y + 1) * gw);
          std::reverse(valid.begin() + long(y) * gw, valid.begin() + long(y + 1) * gw);
        }
    } else {
      px = py = opt.assumedCellSize > 0.0 && std::isfinite(opt.assumedCellSize) ? opt.assumedCellSize : 1.0;
      sw = {0.0, 0.0};
    }
    if (src) outWkt = srsWkt(src);
  }
  // GDAL may report a read failure and still hand back heights: a GeoTIFF
  // cut in its tag data warns "IO error during reading of ...; tag
  // ignored", and its tile offsets past the cut read as zero, so those tiles
  // come back as empty, not as an error. Any such message means the heights
  // cannot be trusted.
  if (const std::string why = gdalErrors.firstReadProblem(); !why.empty())
    fail("the file is damaged or truncated (" + why + ")");
  if (tgt) {
    rep.targetCrs = srsName(tgt);
    rep.targetEpsg = srsEpsg(tgt);
  } else {
    rep.targetCrs = rep.sourceCrs;
    rep.targetEpsg = rep.sourceEpsg;
  }

  // --- vertical units ------------------------------------------------------
  int hasScale = 0, hasOffset = 0;
  double scale = GDALGetRasterScale(band, &hasScale), offset = GDALGetRasterOffset(band, &hasOffset);
  if (!hasScale || !std::isfinite(scale) || scale == 0.0) scale = 1.0;
  if (!hasOffset || !std::isfinite(offset)) offset = 0.0;
  std::string unitName;
  const double unitScale = verticalUnitScale(GDALGetRasterUnitType(band), unitName);
  rep.verticalScale = scale * unitScale;
  if (scale != 1.0 || offset != 0.0 || unitScale != 1.0) {
    for (size_t i = 0; i < values.size(); ++i)
      if (valid[i]) values[i] = float((double(values[i]) * scale + offset) * unitScale);
    rep.warnings.push_back("heights converted to metres (scale " + fmt(scale) + ", offset " + fmt(offset) +
                           ", unit " + unitName + ")");
  }
  size_t absurd = 0;
  for (size_t i = 0; i < values.size(); ++i)
    if (valid[i] && std::abs(values[i]) > 1e5f) {
      valid[i] = 0;
      ++absurd;
    }
  if (absurd)
    rep.warnings.push_back(std::to_string(absurd) + " samples above 100 km in magnitude treated as nodata");

  // --- nodata ------------------------------------------------------------
  if (std::find(valid.begin(), valid.end(), uint8_t(1)) == valid.end())
    fail(std::string("every sample") + (win.units != DemWindow::Units::Full ? " in the window" : "") +
         " is nodata" + (noData ? " (" + fmt(nd) + ")" : "") + "; there is no elevation to import");
  for (const auto& w : gdalErrors.warnings()) rep.warnings.push_back("GDAL: " + w);
  out.width = gw;
  out.height = gh;
  out.values = std::move(values);
  out.valid = std::move(valid);
  out.spacing = {px, py};
  out.southWest = sw;
  out.crsWkt = std::move(outWkt);
}

}  // namespace

bool gdal_side::readDem(const std::string& path, const DemImportOptions& options, const Progress* progress,
                        gdal_door::DemRaster& out, DemImportReport& report, std::string& error, bool& cancelled) {
  // Fail is thrown only inside read() and caught here: no exception crosses
  // the module's boundary.
  cancelled = false;
  try {
    read(path, options, progress, out, report, cancelled);
    return true;
  } catch (const Fail& f) {
    error = f.msg;
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
  }
  cancelled = cancelled || isCancelled(progress);
  return false;
}

}  // namespace hs::terrain
