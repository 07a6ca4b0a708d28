#include "terrain/dem_export.h"

#include <cfloat>
#include <filesystem>

#include <cpl_string.h>
#include <gdal.h>

#include "terrain/gdal_util.h"
#include "terrain/heightmap_image.h"

namespace hs::terrain {

Status exportGeoTiff(const Heightfield& hf, const std::string& path, bool holesAsNodata) {
  ensureGdalRegistered();
  GdalErrorCapture errors;
  GDALDriverH drv = GDALGetDriverByName("GTiff");
  if (!drv) return Status::failure(path + ": this GDAL has no GeoTIFF driver");
  const int w = hf.samplesX(), h = hf.samplesY();
  std::vector<float> v = detail::heightsNorthFirst(hf);
  bool anyHole = false;
  constexpr double kNodata = -FLT_MAX;  // the ESRI convention for float rasters
  if (holesAsNodata)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (hf.isHole(x, y)) {
          v[size_t(h - 1 - y) * size_t(w) + size_t(x)] = float(kNodata);
          anyHole = true;
        }
  // Written beside the target and renamed over it: a failed export never
  // leaves a half-written file under the user's name.
  const std::string tmp = path + ".part.tif";
  char** co = nullptr;
  co = CSLSetNameValue(co, "COMPRESS", "DEFLATE");
  co = CSLSetNameValue(co, "PREDICTOR", "3");
  co = CSLSetNameValue(co, "TILED", "YES");
  co = CSLSetNameValue(co, "BIGTIFF", "IF_SAFER");
  DatasetPtr ds(GDALCreate(drv, tmp.c_str(), w, h, 1, GDT_Float32, co));
  CSLDestroy(co);
  if (!ds) return Status::failure(path + ": cannot create the GeoTIFF (" + errors.lastError() + ")");
  // Pixel-is-area: the top-left corner is half a pixel west and north of
  // the north-west sample.
  const glm::dvec2 sp = hf.spacing();
  const glm::dvec3 o = hf.origin();
  double gt[6] = {o.x - 0.5 * sp.x, sp.x, 0.0, o.y + (h - 1) * sp.y + 0.5 * sp.y, 0.0, -sp.y};
  GDALSetGeoTransform(ds.get(), gt);
  if (hf.geo().valid()) GDALSetProjection(ds.get(), hf.geo().crsWkt.c_str());
  GDALSetMetadataItem(ds.get(), "AREA_OR_POINT", "Area", nullptr);
  GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
  if (anyHole) GDALSetRasterNoDataValue(band, kNodata);
  GDALSetRasterUnitType(band, "m");
  if (o.z != 0.0) GDALSetRasterOffset(band, o.z);
  if (GDALRasterIO(band, GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0) != CE_None) {
    ds.reset();
    std::filesystem::remove(tmp);
    return Status::failure(path + ": write failed (" + errors.lastError() + ")");
  }
  ds.reset();  // GDALClose flushes
  if (!errors.lastError().empty()) {
    std::filesystem::remove(tmp);
    return Status::failure(path + ": write failed (" + errors.lastError() + ")");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return Status::failure(path + ": cannot move the finished file into place (" + ec.message() + ")");
  return {};
}

}  // namespace hs::terrain
