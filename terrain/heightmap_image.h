#pragma once
// Heightmaps as images and raw files, the formats game engines and other
// terrain tools exchange (Unreal's 16-bit PNG and .r16, Gaea/World Machine
// EXR), both ways:
//   16-bit PNG: heights mapped to 0..65535 over a recorded range (PNG text
//               chunks "hs:height_min/max", plus spacing, origin and CRS)
//   EXR:        32-bit float heights, exact; the same metadata as attributes
//   RAW .r16:   little-endian uint16, north row first, with a JSON sidecar
//               (<file>.json) giving size, range, spacing, origin, CRS, and the
//               Unreal Z scale that reproduces the range
// An exported file imports back to the same terrain: exact for EXR, within
// half a quantisation step ((max - min) / 65535 / 2) for 16-bit formats.
#include <optional>
#include <string>
#include <vector>

#include "core/params.h"
#include "terrain/heightfield.h"
#include "terrain/paint_layers.h"

namespace hs::terrain {

enum class HeightmapFormat { Png16, Exr32, GeoTiff, RawR16 };
// From the extension (.png .exr .tif/.tiff .r16/.raw); nullopt if unknown.
std::optional<HeightmapFormat> heightmapFormatFor(const std::string& path);

struct HeightExportOptions {
  std::optional<HeightRange> range;  // 16-bit formats; default: the terrain's min..max
  bool holesAsNodata = true;         // GeoTIFF: holes become nodata
};

// Heights a user may give a terrain or an export range, metres: ±100 km,
// beyond any relief on Earth and inside what a float keeps to a centimetre.
inline constexpr double kMaxTerrainHeightMetres = 1e5;

// HeightExportOptions' parameters and the paint weights' format, declared
// once (`terrain export`): range, weights_format.
const std::vector<ParamDecl>& heightExportParamDecls();

struct HeightExportReport {
  std::string file;
  std::string sidecar;               // RAW: the JSON file written beside it
  HeightRange range;                 // what 0 and 65535 mean (16-bit formats)
  double quantisationStep = 0.0;     // metres per 16-bit step (0 for float formats)
  int width = 0, height = 0;
  size_t clampedSamples = 0;         // outside a user-given range
};

Result<HeightExportReport> exportHeightmap(const Heightfield& hf, const std::string& path,
                                           const HeightExportOptions& options = {});

struct HeightmapImportOptions {
  // For files without our metadata: the height range of a 16-bit file, and
  // the ground size (first to last sample) of any file.
  std::optional<HeightRange> range;
  std::optional<glm::dvec2> sizeMetres;
};

// PNG/EXR/TIFF through OpenImageIO, .r16/.raw with their sidecar. Anything
// else (georeferenced DEMs) goes through importDem().
Result<Heightfield> importHeightmap(const std::string& path, const HeightmapImportOptions& options = {},
                                    std::vector<std::string>* warnings = nullptr);

// Paint weights as images: one layer as a grey image (8- or 16-bit PNG,
// TIFF; float EXR), or four layers (first..first+3) as an RGBA 8-bit splat map.
Result<std::string> exportPaintLayerImage(const PaintLayers& paint, int layer, const std::string& path, int bits = 8);
Result<std::string> exportSplatMap(const PaintLayers& paint, int firstLayer, const std::string& path);

namespace detail {
// Image rows run north first; heightfield rows run south first.
std::vector<float> heightsNorthFirst(const Heightfield& hf);
}  // namespace detail

}  // namespace hs::terrain
