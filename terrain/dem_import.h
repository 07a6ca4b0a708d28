#pragma once
// DEM import through GDAL: GeoTIFF, DTED, SRTM .hgt, ASCII grid and anything
// else GDAL reads as a raster.
//
// Ground size: a terrain is built in metres on the ground. A DEM whose CRS
// does not measure ground metres (geographic degrees; Web Mercator, whose
// "metres" are 1/cos(latitude) too long; feet) is reprojected with GDALWarp
// to a local metric CRS. The decision is measured, not guessed from the CRS
// name: the geodesic (WGS 84 ellipsoid) distance across the window is
// compared with the CRS's own distance, and more than 0.5% disagreement means
// "reproject". The output is the largest axis-aligned rectangle inside the
// reprojected footprint, so no corner of the terrain is invented.
// The default local CRS is a transverse Mercator centred on the DEM (on its
// own datum): zero meridian convergence at the centre, so a lat/lon-aligned
// DEM stays aligned with the terrain grid and keeps its full ground size
// (scale error < 0.01% within 50 km of the centre). The UTM zone of the
// centre is the alternative (DemCrsMode::Utm): standard coordinates, but its
// grid is rotated against the DEM's by the meridian convergence (0.9 degrees
// for the test DEM, up to about 3 degrees at zone edges), so the axis-aligned
// crop loses a sliver (1.8% of the width for the test DEM). Several DEMs of
// one scene must share one CRS: import the first with Auto, the next ones
// with Custom and the first terrain's geo().crsWkt.
// The terrain keeps the CRS (WKT) and its origin in that CRS, so exports line
// up with the source in a GIS.
//
// Nodata: filled (nodata_fill.h) and reported: how many samples, how many
// voids, by which method. Sample convention: terrain samples are the centres
// of the DEM's pixels (of the reprojected raster, if any).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/params.h"
#include "core/progress.h"
#include "terrain/grid_resample.h"
#include "terrain/heightfield.h"
#include "terrain/nodata_fill.h"

namespace hs::terrain {

// Part of a large DEM to import.
struct DemWindow {
  enum class Units {
    Full,       // the whole raster
    Pixels,     // columns [minX, maxX), rows [minY, maxY); row 0 is the file's first (usually northern) row
    SourceCrs,  // a box in the file's own CRS units
    LonLat,     // a box in WGS 84 degrees
  };
  Units units = Units::Full;
  double minX = 0, minY = 0, maxX = 0, maxY = 0;
};

enum class DemCrsMode {
  Auto,        // keep a metric CRS; reproject degrees/Mercator/feet to a local transverse Mercator
  KeepSource,  // never reproject (refused for geographic CRSs: degrees are not a size)
  LocalTransverseMercator,  // always reproject, to a TM centred on the DEM
  Utm,         // always reproject, to the WGS 84 UTM zone of the centre
  Custom,      // reproject to `customCrs` (WKT, "EPSG:n", PROJ string), e.g. the scene's CRS
};

struct DemImportOptions {
  int band = 1;
  DemWindow window;
  DemCrsMode crs = DemCrsMode::Auto;
  std::string customCrs;
  Resampling resampling = Resampling::Bilinear;  // for reprojection and for resizing
  int samplesX = 0, samplesY = 0;  // 0: the DEM's own resolution (at most 8193 per side)
  NodataFill fill = NodataFill::Diffusion;
  double idwMaxDistancePixels = 0.0;  // InverseDistance search radius; 0 = 100 pixels
  std::optional<double> nodataValue;  // overrides the file's nodata value
  double assumedCellSize = 1.0;       // metres per pixel for rasters with no georeferencing
};

struct DemImportReport {
  std::string file;
  std::string driver;
  int sourceWidth = 0, sourceHeight = 0;
  std::string sourceCrs;
  int sourceEpsg = 0;
  int windowX = 0, windowY = 0, windowW = 0, windowH = 0;  // source pixels read
  bool reprojected = false;
  std::string targetCrs;
  int targetEpsg = 0;
  double sourceScaleError = 0.0;  // |CRS distance / ground distance - 1| across the window
  std::string resampling;
  bool hasNodata = false;
  double nodataValue = 0.0;
  FillReport fill;
  int samplesX = 0, samplesY = 0;
  glm::dvec2 spacing{0.0};
  glm::dvec2 groundSize{0.0};  // metres, first to last sample
  glm::dvec2 origin{0.0};      // of sample (0,0) (south-west), in the target CRS
  float heightMin = 0.0f, heightMax = 0.0f;
  double verticalScale = 1.0;
  std::vector<std::string> warnings;
  double seconds = 0.0;
};

// DemImportOptions' parameters, declared once (`terrain import`, the Import
// DEM dialog): window (text, see parseDemWindow), window_box (the window's
// four numbers, the dialog's fields), samples, crs, resampling, fill,
// nodata.
const std::vector<ParamDecl>& demImportParamDecls();
// "[pixels:|crs:|lonlat:]MINX,MINY,MAXX,MAXY" (the CLI's --window; pixels
// when no kind is given). False with `error` naming --window otherwise.
bool parseDemWindow(const std::string& text, DemWindow& out, std::string& error);

struct DemImportResult {
  std::optional<Heightfield> heightfield;
  DemImportReport report;
  std::string error;  // names the file
  bool cancelled = false;
  bool ok() const { return heightfield.has_value(); }
};

DemImportResult importDem(const std::string& path, const DemImportOptions& options = {},
                          const Progress* progress = nullptr);

// One-line summary for logs and the CLI ("dem.tif: 367x359 EPSG:4326 -> ...").
std::string summary(const DemImportReport& r);

}  // namespace hs::terrain
