#include "terrain/terrain_operations.h"

#include "terrain/dem_import.h"
#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"
#include "terrain/heightmap_image.h"
#include "terrain/paint_layers.h"

namespace hs::terrain {
namespace {

const PositionalDecl kScene{.name = "scene.hscene", .help = "the scene file (saved afterwards)"};

ParamDecl terrainName() {
  return {.key = "terrain", .option = "terrain", .label = "Terrain", .type = ParamType::Text,
          .help = "which terrain (needed when the scene has several)", .valueName = "NAME"};
}

ParamDecl flag(const char* key, const char* label, const char* help, const char* group = "") {
  return {.key = key, .option = key, .label = label, .type = ParamType::Flag, .help = help, .group = group};
}

ParamDecl text(const char* key, const char* label, const char* help, const char* valueName) {
  return {.key = key, .option = key, .label = label, .type = ParamType::Text, .help = help, .valueName = valueName};
}

}  // namespace

const OperationDecl& terrainErodeOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "terrain erode",
        .summary = "thermal or hydraulic erosion over a terrain; prints the mass error",
        .usage = "<scene.hscene> --thermal|--hydraulic [options]",
        .description = "Erodes a whole terrain (or where a paint layer is painted) as one undo step, prints the "
                       "solver's mass error and time, and saves the scene. Values outside the ranges below are "
                       "refused; the solvers cannot blow up within them.",
        .positionals = {kScene}};
    const ThermalParams t;
    const HydraulicParams h;
    ParamDecl iterations = paramIn(thermalParamDecls(), "iterations");
    iterations.defaultValue = nullptr;  // the solver's: thermal 50, hydraulic 300
    iterations.help = "solver iterations; default thermal " + std::to_string(t.iterations) + ", hydraulic " +
                      std::to_string(h.iterations);
    o.params = {
        terrainName(),
        flag("thermal", "Thermal", "thermal erosion (talus creep)"),
        flag("hydraulic", "Hydraulic", "hydraulic erosion (rain, flow, sediment)"),
        iterations,
        {.key = "mask_layer", .option = "mask-layer", .label = "Where", .min = 0, .max = kMaxPaintLayers - 1,
         .integer = true, .help = "erode only where paint layer N is painted (weighted)", .valueName = "N"},
        {.key = "threads", .option = "threads", .label = "Threads", .min = 0, .max = 256, .integer = true,
         .defaultValue = 0, .help = "worker threads (0: all)", .valueName = "N"},
    };
    for (const ParamDecl& p : thermalParamDecls())
      if (p.key != "iterations") o.params.push_back(p);
    for (const ParamDecl& p : hydraulicParamDecls())
      if (p.key != "iterations" && !p.option.empty()) o.params.push_back(p);
    return o;
  }();
  return op;
}

const OperationDecl& terrainImportOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "terrain import",
        .summary = "import a DEM (GeoTIFF, DTED, .hgt, ASCII grid, ...) as a terrain",
        .usage = "<dem> <scene.hscene> [options]",
        .description = "Imports an elevation model (GeoTIFF, DTED, SRTM .hgt, ASCII grid, anything GDAL reads) as a "
                       "new terrain at its true ground size in metres, keeping its CRS and georeferenced origin, "
                       "and saves the scene. Nodata is filled and reported.",
        .positionals = {{.name = "dem", .help = "the elevation model"}, kScene}};
    o.params = demImportParamDecls();
    o.params.push_back(text("name", "Name",
                            "entity and terrain name (default: the file's base name; if that is taken, the first "
                            "free 'name 2', 'name 3', ...)",
                            "NAME"));
    o.params.push_back(text("into", "Into",
                            "replace the heights of existing terrain NAME instead: the DEM is resampled onto that "
                            "terrain's grid (one undo step)",
                            "NAME"));
    return o;
  }();
  return op;
}

const OperationDecl& terrainExportOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "terrain export",
        .summary = "write heights (16-bit PNG, EXR, GeoTIFF, RAW r16) and paint weights",
        .usage = "<scene.hscene> --out FILE [--weights DIR] [options]",
        .description = "Writes a terrain's heights; the format follows the extension:\n"
                       "  .png  16-bit, heights mapped over their range (recorded in the file)\n"
                       "  .exr  32-bit float, exact\n"
                       "  .tif  GeoTIFF, 32-bit float with the terrain's CRS, holes as nodata\n"
                       "  .r16  RAW little-endian 16-bit (Unreal) with a .json sidecar (range, Z scale)",
        .positionals = {{.name = "scene.hscene", .help = "the scene file"}}};
    o.params = {terrainName(), text("out", "Heightmap", "the heightmap file to write", "FILE"),
                text("weights", "Weights folder", "also write every paint layer's weights into DIR", "DIR")};
    appendParams(o.params, heightExportParamDecls());
    return o;
  }();
  return op;
}

const OperationDecl& terrainPaintRulesOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "terrain paint-rules",
        .summary = "paint a terrain's layers by slope and altitude",
        .usage = "<scene.hscene> [options]",
        .description = "Paints a terrain's layers automatically by altitude and slope with its paint rules (one "
                       "undo step; weights stay summing to 1), and saves the scene.",
        .positionals = {kScene}};
    o.params = {terrainName(),
                text("rules", "Rules",
                     "use these rules (a JSON array: layer, strength, enabled, use_altitude, altitude_min, "
                     "altitude_max, altitude_blend, use_slope, slope_min, slope_max, slope_blend) and keep them as "
                     "the terrain's rules",
                     "FILE"),
                flag("defaults", "Defaults", "reset the terrain's rules to the defaults first"),
                flag("show", "Show", "print the rules and change nothing")};
    return o;
  }();
  return op;
}

const OperationDecl& terrainLayerOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "terrain layer",
        .summary = "show or change a paint layer's material (albedo, textures, normal map, roughness, tiling)",
        .usage = "<scene.hscene> --layer N [options]",
        .description = "Changes the material of one paint layer of a terrain (one undo step) and saves the scene; "
                       "with no change given, prints the terrain's layers. Texture and normal-map files must be "
                       "readable images; they are stored by absolute path, and \"none\" removes one.",
        .positionals = {kScene}};
    const Material d;
    o.params = {
        terrainName(),
        {.key = "layer", .option = "layer", .label = "Layer", .min = 0, .max = kMaxPaintLayers - 1, .integer = true,
         .help = "which paint layer (0: the base layer)", .valueName = "N"},
        text("name", "Name", "the material's name", "NAME"),
        {.key = "albedo", .option = "albedo", .label = "Albedo", .min = 0.0, .max = 1.0,
         .help = "linear RGB colour (the tint of the albedo texture)", .valueName = "r,g,b", .count = 3},
        {.key = "albedo_texture", .option = "albedo-texture", .label = "Albedo texture", .type = ParamType::Text,
         .help = "colour texture (sRGB image), or none", .valueName = "FILE"},
        {.key = "normal_map", .option = "normal-map", .label = "Normal map", .type = ParamType::Text,
         .help = "tangent-space normal map (x right, y up the texture, z out), or none", .valueName = "FILE"},
        {.key = "roughness", .option = "roughness", .label = "Roughness", .min = 0.0, .max = 1.0,
         .help = "surface roughness (0 mirror-like, 1 matte; a new layer has " + std::to_string(d.roughness).substr(0, 4) + ")", .valueName = "X",
         .decimals = 2, .step = 0.05},
        {.key = "tiling_m", .option = "tiling", .label = "Tiling", .unit = Unit::Metres, .min = 0.01, .max = 10000.0,
         .help = "world size of one texture repeat", .valueName = "M",
         .decimals = 2, .step = 0.5},
    };
    return o;
  }();
  return op;
}

}  // namespace hs::terrain
