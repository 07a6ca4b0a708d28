#pragma once
// GeoTIFF export through GDAL: 32-bit float heights (exact), the terrain's
// CRS and a geotransform that puts every pixel centre on its sample, so the
// export lines up with the DEM it came from in any GIS. Holes become nodata.
// (16-bit PNG, EXR and RAW exports: heightmap_image.h; exportHeightmap()
// picks by extension and sends .tif here.)
#include <string>

#include "terrain/heightfield.h"

namespace hs::terrain {

Status exportGeoTiff(const Heightfield& hf, const std::string& path, bool holesAsNodata = true);

}  // namespace hs::terrain
