#pragma once
// The GDAL module's calls (terrain/gdal_door.h's Backend), one file each:
// dem_read_gdal.cpp, nodata_idw_gdal.cpp, geotiff_write_gdal.cpp,
// crs_transform_gdal.cpp, and the
// module's entry point (gdal_module.cpp) that hands them out. Nothing in
// hs_terrain includes this: it goes through the door.
#include "terrain/gdal_door.h"

namespace hs::terrain::gdal_side {

bool readDem(const std::string& path, const DemImportOptions& options, const Progress* progress,
             gdal_door::DemRaster& out, DemImportReport& report, std::string& error, bool& cancelled);
void fillInverseDistance(std::vector<float>& values, std::vector<uint8_t>& valid, int width, int height,
                         double maxDistancePixels, const Progress* progress);
Status writeGeoTiff(const gdal_door::GeoTiffRaster& raster, const std::string& path);
bool transformPoints(const std::string& from, const std::string& to, std::vector<glm::dvec3>& points,
                     std::string& toDefinition, std::string& toName, std::string& error);

}  // namespace hs::terrain::gdal_side
