#include "terrain/dem_export.h"

#include <cfloat>

#include "terrain/gdal_door.h"
#include "terrain/heightmap_image.h"

namespace hs::terrain {

Status exportGeoTiff(const Heightfield& hf, const std::string& path, bool holesAsNodata) {
  std::string missing;
  const gdal_door::Backend* gdal = gdal_door::backend(missing);
  if (!gdal) return Status::failure(path + ": cannot write a GeoTIFF: " + missing);
  gdal_door::GeoTiffRaster r;
  const int w = hf.samplesX(), h = hf.samplesY();
  r.width = w;
  r.height = h;
  r.northFirst = detail::heightsNorthFirst(hf);
  constexpr double kNodata = -FLT_MAX;  // the ESRI convention for float rasters
  if (holesAsNodata)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (hf.isHole(x, y)) {
          r.northFirst[size_t(h - 1 - y) * size_t(w) + size_t(x)] = float(kNodata);
          r.hasNodata = true;
        }
  r.nodata = kNodata;
  // Pixel-is-area: the top-left corner is half a pixel west and north of
  // the north-west sample.
  const glm::dvec2 sp = hf.spacing();
  const glm::dvec3 o = hf.origin();
  const double gt[6] = {o.x - 0.5 * sp.x, sp.x, 0.0, o.y + (h - 1) * sp.y + 0.5 * sp.y, 0.0, -sp.y};
  std::copy(std::begin(gt), std::end(gt), r.geoTransform);
  if (hf.geo().valid()) r.crsWkt = hf.geo().crsWkt;
  r.heightOffset = o.z;
  return gdal->writeGeoTiff(r, path);
}

}  // namespace hs::terrain
