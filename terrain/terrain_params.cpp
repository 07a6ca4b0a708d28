// Parameters of DEM import and heightmap export, declared once
// (core/params.h), and the DEM window notation of `terrain import --window`.
#include <cfloat>

#include "terrain/dem_import.h"
#include "terrain/heightmap_image.h"
#include "terrain/heightfield.h"

namespace hs::terrain {

const std::vector<ParamDecl>& demImportParamDecls() {
  static const std::vector<ParamDecl> decls = {
      {.key = "window", .option = "window", .label = "Part", .type = ParamType::Text,
       .help = "import only this part (pixels: columns/rows, row 0 = the file's first row; crs: the file's CRS "
               "units; lonlat: WGS 84 degrees)",
       .valueName = "[pixels:|crs:|lonlat:]MINX,MINY,MAXX,MAXY"},
      // The window's four numbers: the dialog's fields; --window reads them too.
      {.key = "window_box", .label = "Window (min x, min y, max x, max y)", .min = -1e9, .max = 1e9,
       .help = "min x / column / longitude, min y / row / latitude, max x, max y", .count = 4, .editor = true,
       .decimals = 6},
      {.key = "samples", .option = "resolution", .label = "Resolution", .unit = Unit::Samples, .min = kMinSamples,
       .max = double(kMaxSamples), .integer = true,
       .help = "resample to N (or WxH) samples; without it, the DEM's own resolution", .valueName = "N",
       .count = 2, .separator = 'x', .oneForAll = true, .editor = true},
      {.key = "crs", .option = "crs", .label = "Coordinates", .type = ParamType::Text, .defaultValue = "auto",
       .help = "target CRS: auto (degrees, Web Mercator and feet are reprojected to a local transverse Mercator), "
               "keep, local, utm (the UTM zone of the centre), EPSG:n or WKT",
       .valueName = "auto|keep|local|utm|EPSG:n|WKT"},
      {.key = "resampling", .option = "resampling", .label = "Resampling", .type = ParamType::Choice,
       .defaultValue = "bilinear", .choices = {"nearest", "bilinear", "cubic"},
       .help = "how samples are interpolated when reprojecting or resizing", .valueName = "R", .editor = true},
      {.key = "fill", .option = "fill", .label = "Fill nodata", .type = ParamType::Choice, .defaultValue = "diffusion",
       .choices = {"diffusion", "idw"},
       .help = "how nodata is filled: diffusion (the smoothest surface over the gap) or idw (inverse distance, "
               "then diffusion)",
       .valueName = "F", .editor = true},
      // Heights are floats: any value a float holds can be a nodata marker
      // (GDAL files often use -FLT_MAX).
      {.key = "nodata", .option = "nodata", .label = "Nodata value", .min = -double(FLT_MAX), .max = double(FLT_MAX),
       .help = "treat this value as nodata (overrides the file's)", .valueName = "V"},
  };
  return decls;
}

bool parseDemWindow(const std::string& text, DemWindow& w, std::string& error) {
  const auto colon = text.find(':');
  const std::string kind = colon == std::string::npos ? "pixels" : text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? text : text.substr(colon + 1);
  if (kind == "pixels") w.units = DemWindow::Units::Pixels;
  else if (kind == "crs") w.units = DemWindow::Units::SourceCrs;
  else if (kind == "lonlat") w.units = DemWindow::Units::LonLat;
  else {
    error = "--window: kind '" + kind + "' is not pixels, crs or lonlat";
    return false;
  }
  ParamDecl box = paramIn(demImportParamDecls(), "window_box");
  box.option = "window";
  box.valueName = "[pixels:|crs:|lonlat:]MINX,MINY,MAXX,MAXY";
  const std::optional<Json> v = parseParam(box, rest, error);
  if (!v) return false;
  w.minX = (*v)[0].get<double>();
  w.minY = (*v)[1].get<double>();
  w.maxX = (*v)[2].get<double>();
  w.maxY = (*v)[3].get<double>();
  if (!(w.maxX > w.minX && w.maxY > w.minY)) {
    error = "--window: MAXX must exceed MINX and MAXY must exceed MINY";
    return false;
  }
  return true;
}

const std::vector<ParamDecl>& heightExportParamDecls() {
  static const std::vector<ParamDecl> decls = {
      {.key = "range_m", .option = "range", .label = "Height range", .unit = Unit::Metres,
       .min = -kMaxTerrainHeightMetres, .max = kMaxTerrainHeightMetres,
       .help = "the 16-bit formats' height range, MIN < MAX (default: the terrain's)", .valueName = "MIN,MAX",
       .count = 2, .ordered = true},
      {.key = "weights_format", .option = "weights-format", .label = "Weights format", .type = ParamType::Choice,
       .defaultValue = "png", .choices = {"png", "png8", "exr"},
       .help = "16-bit PNG, 8-bit PNG or float EXR for the paint weights", .valueName = "F"},
  };
  return decls;
}

}  // namespace hs::terrain
