// Writing a float GeoTIFF through GDAL, the GDAL side of dem_export.h.
// Built into the GDAL module (terrain/gdal_door.h), not into hs_terrain.
#include <filesystem>

#include <cpl_string.h>
#include <gdal.h>

#include "terrain/gdal_side.h"
#include "terrain/gdal_util.h"

namespace hs::terrain {

Status gdal_side::writeGeoTiff(const gdal_door::GeoTiffRaster& r, const std::string& path) {
  ensureGdalRegistered();
  GdalErrorCapture errors;
  GDALDriverH drv = GDALGetDriverByName("GTiff");
  if (!drv) return Status::failure(path + ": this GDAL has no GeoTIFF driver");
  // Written beside the target and renamed over it: a failed export never
  // leaves a half-written file under the user's name.
  const std::string tmp = path + ".part.tif";
  char** co = nullptr;
  co = CSLSetNameValue(co, "COMPRESS", "DEFLATE");
  co = CSLSetNameValue(co, "PREDICTOR", "3");
  co = CSLSetNameValue(co, "TILED", "YES");
  co = CSLSetNameValue(co, "BIGTIFF", "IF_SAFER");
  DatasetPtr ds(GDALCreate(drv, tmp.c_str(), r.width, r.height, 1, GDT_Float32, co));
  CSLDestroy(co);
  if (!ds) return Status::failure(path + ": cannot create the GeoTIFF (" + errors.lastError() + ")");
  double gt[6];
  std::copy(std::begin(r.geoTransform), std::end(r.geoTransform), gt);
  GDALSetGeoTransform(ds.get(), gt);
  if (!r.crsWkt.empty()) GDALSetProjection(ds.get(), r.crsWkt.c_str());
  GDALSetMetadataItem(ds.get(), "AREA_OR_POINT", "Area", nullptr);
  GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
  if (r.hasNodata) GDALSetRasterNoDataValue(band, r.nodata);
  GDALSetRasterUnitType(band, "m");
  if (r.heightOffset != 0.0) GDALSetRasterOffset(band, r.heightOffset);
  if (GDALRasterIO(band, GF_Write, 0, 0, r.width, r.height, const_cast<float*>(r.northFirst.data()), r.width,
                   r.height, GDT_Float32, 0, 0) != CE_None) {
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
