#pragma once
// GDAL and PROJ (elevation models in, GeoTIFF out, GDAL's inverse-distance
// nodata fill, coordinate reference systems): the one door the terrain
// library goes through to them.
//
// Why a door and not GDAL directly: linking libgdal loads 114 shared
// libraries at every process start (0.07-0.11 s and 34 MB for an empty
// program on this project's machines), DEM or not, which was half of
// `hybridscape-cli --version` and of every one of the CLI's hundreds of
// starts in the test suite. GDAL now lives in a module of its own
// (dem_read_gdal.cpp, geotiff_write_gdal.cpp, nodata_idw_gdal.cpp, built as
// hybridscape-gdal.so), loaded on the first call here, the way OpenImageIO
// is (core/image_io.h; the same loader, core/module_loader.h). The rest of
// a DEM import (nodata fill, resizing, the heightfield) and everything else
// in the library stays here.
//
// The module is found at $HS_GDAL_MODULE when set, else where the build put
// it, else beside the running program. Without it a DEM import or a GeoTIFF
// export fails with a message naming where it looked; nothing else changes.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/progress.h"
#include "terrain/dem_import.h"
#include "terrain/result.h"

namespace hs::terrain::gdal_door {

// A DEM's window as GDAL read it: heights in metres (scale, offset and
// vertical unit applied), rows north first, columns west first, in the
// target CRS (the file's, or the one it was reprojected to).
struct DemRaster {
  int width = 0, height = 0;
  std::vector<float> values;
  std::vector<uint8_t> valid;  // 1 = a measured height, 0 = nodata
  glm::dvec2 spacing{1.0};     // metres between samples
  glm::dvec2 southWest{0.0};   // centre of the south-west sample, in the target CRS
  std::string crsWkt;          // "" without a CRS
};

// A float GeoTIFF to write.
struct GeoTiffRaster {
  int width = 0, height = 0;
  std::vector<float> northFirst;  // width * height heights, north row first
  double geoTransform[6] = {0, 1, 0, 0, 0, -1};
  std::string crsWkt;           // "" without a CRS
  bool hasNodata = false;       // holes are written as `nodata`
  double nodata = 0.0;
  double heightOffset = 0.0;    // the band's offset (the terrain's origin z)
};

// The module's side: one object with the calls below, returned by the
// module's `hs_gdal_backend` (extern "C"). Both sides are built together
// from this header, so C++ types cross between them. No call throws.
struct Backend {
  virtual ~Backend() = default;
  // Opens `path`, picks the window and the target CRS, reads (reprojecting
  // where needed) and fills the report's source, window, CRS, nodata and
  // vertical-unit fields and its warnings (GDAL's own last). False with
  // `error` (naming the file) or `cancelled`.
  virtual bool readDem(const std::string& path, const DemImportOptions& options, const Progress* progress,
                       DemRaster& out, DemImportReport& report, std::string& error, bool& cancelled) const = 0;
  // GDALFillNodata over `values` where `valid` is 0, within `maxDistancePixels`;
  // what it fills is marked valid. What it leaves is for the caller.
  virtual void fillInverseDistance(std::vector<float>& values, std::vector<uint8_t>& valid, int width, int height,
                                   double maxDistancePixels, const Progress* progress) const = 0;
  // Writes a tiled, deflated GeoTIFF beside `path` and renames it over it:
  // a failed export never leaves a half-written file under the user's name.
  virtual Status writeGeoTiff(const GeoTiffRaster& raster, const std::string& path) const = 0;
  // Reprojects `points` in place from the CRS `from` to `to` (anything
  // OSRSetFromUserInput takes: "EPSG:4978", WKT, a PROJ string; x and y in
  // GIS order, z carried through: ECEF to a projected CRS gives heights on
  // the ellipsoid). `to` = "utm": the WGS 84 UTM zone holding the points'
  // centre. Fills `toDefinition` ("EPSG:n" when it has that code, else
  // its WKT) and `toName` with the CRS reached. False with
  // `error` for a CRS PROJ does not know or a point it cannot convert.
  virtual bool transformPoints(const std::string& from, const std::string& to, std::vector<glm::dvec3>& points,
                               std::string& toDefinition, std::string& toName, std::string& error) const = 0;
};

// The module's calls (loading it on the first call), or nullptr with
// `error` saying which module is missing and where it was looked for.
const Backend* backend(std::string& error);

// Whether the module is here (loading it if not yet loaded); `where` says
// where it was found or looked.
bool available(std::string* where = nullptr);

}  // namespace hs::terrain::gdal_door
