// `terrain new` declared once: the CLI's options and the New Terrain dialog's
// fields (size, resolution, height range) come from here.
//
// Sizes are 1 m to 1000 km a side (the dialog's limits; a terrain under a
// metre is a typing error, and 8193 samples over 1000 km are 122 m apart,
// already coarser than any DEM worth sculpting). Heights are within
// ±kMaxTerrainHeightMetres of the centre.
#include "core/world_extent.h"
#include "scene/terrain_ops.h"
#include "terrain/heightmap_image.h"

namespace hs::scene::ops {

const OperationDecl& terrainNewOperation() {
  static const OperationDecl op = [] {
    const NewTerrain d;
    const double h = terrain::kMaxTerrainHeightMetres;
    return OperationDecl{
        .name = "terrain new",
        .summary = "add a terrain (flat, or hills within a height range)",
        .usage = "<scene.hscene> --size WxH --resolution N [options]",
        .description = "Adds a terrain and an entity showing it (one undo step in the editor), then saves the scene.",
        .positionals = {{.name = "scene.hscene", .help = "the scene file (saved afterwards)"}},
        .params = {
            {.key = "size_m", .option = "size", .label = "Size (east × north)", .unit = Unit::Metres, .min = 1.0,
             .max = 1e6, .help = "extent in metres, first to last sample (e.g. 2000x2000)", .valueName = "WxH",
             .count = 2, .separator = 'x', .oneForAll = true, .required = true, .editor = true, .decimals = 2},
            {.key = "samples", .option = "resolution", .label = "Resolution", .unit = Unit::Samples,
             .min = terrain::kMinSamples, .max = terrain::kMaxSamples, .integer = true,
             .help = "samples per side (N or WxH, e.g. 2049); spacing = size / (N-1)", .valueName = "N",
             .count = 2, .separator = 'x', .oneForAll = true, .required = true, .editor = true},
            {.key = "name", .option = "name", .label = "Name", .type = ParamType::Text, .defaultValue = d.name,
             .help = "entity and terrain name", .valueName = "NAME"},
            {.key = "height_m", .option = "height", .label = "Height range", .unit = Unit::Metres, .min = -h, .max = h,
             .defaultValue = Json::array({d.heightRange.min, d.heightRange.max}),
             .help = "height range in metres; flat at MIN", .valueName = "MIN,MAX", .count = 2, .editor = true,
             .decimals = 2, .ordered = true},
            {.key = "hills", .option = "hills", .label = "Hills", .type = ParamType::Flag,
             .help = "start from fractal hills spanning the height range"},
            {.key = "seed", .option = "seed", .label = "Seed", .min = 0, .max = 2147483647, .integer = true,
             .defaultValue = d.seed, .help = "seed of the hills", .valueName = "N"},
            {.key = "at_m", .option = "at", .label = "Centre", .unit = Unit::Metres, .min = -kWorldExtentMetres,
             .max = kWorldExtentMetres, .defaultValue = Json::array({d.centre.x, d.centre.y, d.centre.z}),
             .help = "world position of the terrain's centre", .valueName = "x,y,z", .count = 3},
            {.key = "lod_error_px", .option = "lod-error", .label = "LOD error", .unit = Unit::Pixels, .min = 0.1,
             .max = 64.0, .defaultValue = d.lodErrorPixels,
             .help = "screen-space error bound of the terrain's level of detail", .valueName = "PX"},
        }};
  }();
  return op;
}

}  // namespace hs::scene::ops
