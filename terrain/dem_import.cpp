#include "terrain/dem_import.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "terrain/gdal_door.h"

namespace hs::terrain {
namespace {

struct Fail {
  std::string msg;
};

// Everything after GDAL's part (gdal_door's readDem): nodata, resizing and
// the heightfield. Throws Fail.
void finish(const std::string& path, const DemImportOptions& opt, const Progress* progress,
            gdal_door::DemRaster& raster, DemImportResult& res) {
  DemImportReport& rep = res.report;
  std::vector<float>& values = raster.values;
  const int gw = raster.width, gh = raster.height;
  auto fail = [&](const std::string& m) { throw Fail{path + ": " + m}; };

  // --- nodata ------------------------------------------------------------
  reportProgress(progress, 0.65, "filling nodata");
  if (!fillNodata(values, raster.valid, gw, gh, opt.fill, opt.idwMaxDistancePixels, rep.fill, progress))
    fail("no valid elevation to fill from");
  if (rep.fill.filled) {
    const double share = double(rep.fill.filled) / double(values.size());
    char percent[32];
    std::snprintf(percent, sizeof percent, "%.2f", share * 100.0);
    rep.warnings.push_back(std::to_string(rep.fill.filled) + " nodata samples (" + percent + "%) in " +
                           std::to_string(rep.fill.voids) + " voids filled by " + rep.fill.method);
    if (share > 0.5) rep.warnings.push_back("more than half of the terrain is filled, not measured");
  }
  if (isCancelled(progress)) {
    res.cancelled = true;
    throw Fail{path + ": import cancelled"};
  }

  // --- resize ------------------------------------------------------------
  glm::dvec2 spacing = raster.spacing;
  const int outW = opt.samplesX ? opt.samplesX : gw, outH = opt.samplesY ? opt.samplesY : gh;
  if (outW != gw || outH != gh) {
    reportProgress(progress, 0.85, "resampling");
    values = resampleGrid(values, gw, gh, outW, outH, opt.resampling);
    spacing.x *= double(gw - 1) / double(outW - 1);
    spacing.y *= double(gh - 1) / double(outH - 1);
  }

  // --- heightfield (row 0 = south) ------------------------------------------
  HeightfieldDesc desc;
  desc.samplesX = outW;
  desc.samplesY = outH;
  desc.sizeMetres = {spacing.x * (outW - 1), spacing.y * (outH - 1)};
  desc.origin = {raster.southWest.x, raster.southWest.y, 0.0};
  auto hf = Heightfield::create(desc);
  if (!hf) fail(hf.error());
  Heightfield field = hf.take();
  for (int y = 0; y < outH / 2; ++y)  // north-first rows -> south-first
    std::swap_ranges(values.begin() + long(y) * outW, values.begin() + long(y + 1) * outW,
                     values.begin() + long(outH - 1 - y) * outW);
  field.write(field.bounds(), values);  // also computes the tile bounds
  GeoReference geo;
  geo.crsWkt = raster.crsWkt;
  geo.crsName = rep.targetCrs;
  geo.epsg = rep.targetEpsg;
  field.setGeo(geo);

  rep.samplesX = outW;
  rep.samplesY = outH;
  rep.spacing = field.spacing();
  rep.groundSize = field.sizeMetres();
  rep.origin = raster.southWest;
  const HeightRange hr = field.range();
  rep.heightMin = hr.min;
  rep.heightMax = hr.max;
  res.heightfield = std::move(field);
}

}  // namespace

DemImportResult importDem(const std::string& path, const DemImportOptions& options, const Progress* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  DemImportResult res;
  auto failed = [&](std::string error, bool cancelled) {
    // A failed import reports only its file and why.
    DemImportResult partial;
    partial.error = std::move(error);
    partial.report.file = path;
    partial.cancelled = cancelled || isCancelled(progress);
    return partial;
  };
  std::string error;
  const gdal_door::Backend* gdal = gdal_door::backend(error);
  if (!gdal) return failed(path + ": cannot read an elevation model: " + error, false);
  DemImportReport& rep = res.report;
  rep.file = path;
  rep.resampling = resamplingName(options.resampling);
  gdal_door::DemRaster raster;
  bool cancelled = false;
  if (!gdal->readDem(path, options, progress, raster, rep, error, cancelled)) return failed(error, cancelled);
  // Fail is thrown only inside finish() and caught here: no exception
  // crosses the API.
  try {
    finish(path, options, progress, raster, res);
  } catch (const Fail& f) {
    return failed(f.msg, res.cancelled);
  } catch (const std::exception& e) {
    return failed(path + ": " + e.what(), false);
  }
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  reportProgress(progress, 1.0, "done");
  return res;
}

std::string summary(const DemImportReport& r) {
  std::ostringstream s;
  s << r.file << ": " << r.driver << " " << r.sourceWidth << "x" << r.sourceHeight << " " << r.sourceCrs;
  if (r.reprojected) s << " -> " << r.targetCrs;
  s << ", terrain " << r.samplesX << "x" << r.samplesY << " samples, " << r.groundSize.x << " x " << r.groundSize.y
    << " m, heights " << r.heightMin << ".." << r.heightMax << " m";
  if (r.fill.filled) s << ", " << r.fill.filled << " nodata samples filled (" << r.fill.method << ")";
  return s.str();
}

}  // namespace hs::terrain
