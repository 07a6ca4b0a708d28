// GDAL's inverse-distance nodata fill (GDALFillNodata), the GDAL side of
// nodata_fill.h's InverseDistance. Built into the GDAL module
// (terrain/gdal_door.h), not into hs_terrain.
#include <cfloat>
#include <cmath>

#include <gdal.h>
#include <gdal_alg.h>

#include "terrain/gdal_side.h"
#include "terrain/gdal_util.h"

namespace hs::terrain {
namespace {

int gdalProgress(double complete, const char*, void* data) {
  const Progress* p = static_cast<const Progress*>(data);
  if (!p) return TRUE;
  p->report(complete, "filling nodata");
  return p->cancelled() ? FALSE : TRUE;
}

}  // namespace

void gdal_side::fillInverseDistance(std::vector<float>& values, std::vector<uint8_t>& valid, int w, int h,
                                    double maxDistancePixels, const Progress* progress) {
  ensureGdalRegistered();
  GdalErrorCapture capture;
  DatasetPtr ds(GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 1, GDT_Float32, nullptr));
  if (!ds) return;
  GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
  const float sentinel = -FLT_MAX;
  std::vector<float> buf = values;
  for (size_t i = 0; i < buf.size(); ++i)
    if (!valid[i]) buf[i] = sentinel;
  GDALSetRasterNoDataValue(band, double(sentinel));
  if (GDALRasterIO(band, GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Float32, 0, 0) != CE_None) return;
  GDALFillNodata(band, nullptr, maxDistancePixels, 0, 0, nullptr, gdalProgress, const_cast<Progress*>(progress));
  if (GDALRasterIO(band, GF_Read, 0, 0, w, h, buf.data(), w, h, GDT_Float32, 0, 0) != CE_None) return;
  for (size_t i = 0; i < buf.size(); ++i)
    if (!valid[i] && buf[i] != sentinel && std::isfinite(buf[i])) {
      values[i] = buf[i];
      valid[i] = 1;
    }
}

}  // namespace hs::terrain
