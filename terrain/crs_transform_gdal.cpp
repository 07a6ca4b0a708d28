// Points from one coordinate system to another through PROJ (OGR's
// coordinate transformation): what brings a 3D Tiles tileset's ECEF
// vertices into a scene's metres (scene/tileset_import.h).
#include <cmath>

#include <ogr_srs_api.h>

#include "terrain/crs_util.h"
#include "terrain/gdal_side.h"
#include "terrain/gdal_util.h"

namespace hs::terrain::gdal_side {

bool transformPoints(const std::string& from, const std::string& to, std::vector<glm::dvec3>& points,
                     std::string& toDefinition, std::string& toName, std::string& error) {
  ensureGdalRegistered();
  GdalErrorCapture capture;
  SrsPtr src = makeSrs(from);
  if (!src) {
    error = "the coordinate system \"" + from + "\" is not one PROJ knows";
    return false;
  }
  SrsPtr dst;
  if (to == "utm") {
    // The zone of the points' centre (their mean, in lon/lat).
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& p : points) mean += p / double(std::max<size_t>(points.size(), 1));
    SrsPtr geographic = makeSrs("EPSG:4326");
    TransformPtr toLonLat = makeTransform(static_cast<OGRSpatialReferenceH>(src.get()),
                                          static_cast<OGRSpatialReferenceH>(geographic.get()));
    double x = mean.x, y = mean.y, z = mean.z;
    int ok = 0;
    if (!toLonLat || !OCTTransformEx(static_cast<OGRCoordinateTransformationH>(toLonLat.get()), 1, &x, &y, &z, &ok) ||
        !ok) {
      error = "the points' centre has no longitude and latitude in \"" + from + "\" (" + capture.lastError() + ")";
      return false;
    }
    dst = makeSrs("EPSG:" + std::to_string(utmEpsgFor(x, y)));
  } else {
    dst = makeSrs(to);
  }
  if (!dst) {
    error = "the coordinate system \"" + to + "\" is not one PROJ knows";
    return false;
  }
  TransformPtr t = makeTransform(static_cast<OGRSpatialReferenceH>(src.get()), static_cast<OGRSpatialReferenceH>(dst.get()));
  if (!t) {
    error = "no transformation from \"" + from + "\" to \"" + to + "\" (" + capture.lastError() + ")";
    return false;
  }
  // In runs of 64k points: PROJ's array call, three coordinate arrays.
  constexpr size_t kRun = 65536;
  std::vector<double> xs, ys, zs;
  std::vector<int> ok;
  for (size_t at = 0; at < points.size(); at += kRun) {
    const size_t n = std::min(kRun, points.size() - at);
    xs.resize(n), ys.resize(n), zs.resize(n), ok.assign(n, 0);
    for (size_t i = 0; i < n; ++i) xs[i] = points[at + i].x, ys[i] = points[at + i].y, zs[i] = points[at + i].z;
    OCTTransformEx(static_cast<OGRCoordinateTransformationH>(t.get()), int(n), xs.data(), ys.data(), zs.data(),
                   ok.data());
    for (size_t i = 0; i < n; ++i) {
      if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i]) || !std::isfinite(zs[i])) {
        error = "point " + std::to_string(at + i) + " (" + std::to_string(points[at + i].x) + ", " +
                std::to_string(points[at + i].y) + ", " + std::to_string(points[at + i].z) + ") does not convert";
        return false;
      }
      points[at + i] = {xs[i], ys[i], zs[i]};
    }
  }
  const int epsg = srsEpsg(static_cast<OGRSpatialReferenceH>(dst.get()));
  toDefinition = epsg > 0 ? "EPSG:" + std::to_string(epsg) : srsWkt(static_cast<OGRSpatialReferenceH>(dst.get()));
  toName = srsName(static_cast<OGRSpatialReferenceH>(dst.get()));
  return true;
}

}  // namespace hs::terrain::gdal_side
