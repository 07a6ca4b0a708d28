// hybridscape-cli terrain export
#include <cstdio>

#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"
#include "terrain/heightmap_image.h"

namespace hs::cli {

int runTerrainExport(int argc, char** argv) {
  const char* cmd = "terrain export";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"terrain"}, {"out"}, {"weights"}, {"range"}, {"weights-format"}}, args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli terrain export <scene.hscene> --out FILE [--weights DIR] [options]\n\n"
        "Writes a terrain's heights; the format follows the extension:\n"
        "  .png  16-bit, heights mapped over their range (recorded in the file)\n"
        "  .exr  32-bit float, exact\n"
        "  .tif  GeoTIFF, 32-bit float with the terrain's CRS, holes as nodata\n"
        "  .r16  RAW little-endian 16-bit (Unreal) with a .json sidecar (range, Z scale)\n\n"
        "  --terrain NAME     which terrain (needed when the scene has several)\n"
        "  --weights DIR      also write every paint layer's weights into DIR\n"
        "  --weights-format png|png8|exr   16-bit PNG (default), 8-bit PNG or float EXR\n"
        "  --range MIN,MAX    the 16-bit formats' height range (default: the terrain's)\n");
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const auto out = args.get("out");
  if (!out && !args.get("weights")) return usage(cmd, "--out FILE (and/or --weights DIR) is required");
  if (out && !terrain::heightmapFormatFor(*out))
    return fail(cmd, *out + ": unknown heightmap type; use .png (16-bit), .exr, .tif (GeoTIFF) or .r16");
  terrain::HeightExportOptions o;
  if (auto r = args.get("range")) {
    double lo, hi;
    if (!terrain_cli::parsePair(*r, lo, hi, error) || !(hi > lo)) return usage(cmd, "--range takes MIN,MAX with MIN < MAX");
    o.range = terrain::HeightRange{float(lo), float(hi)};
  }
  std::string ext = "png";
  int bits = 16;
  if (auto f = args.get("weights-format")) {
    if (*f == "png8") bits = 8;
    else if (*f == "exr") ext = "exr";
    else if (*f != "png") return usage(cmd, "--weights-format takes png, png8 or exr");
  }
  const std::string path = args.positional[0];
  std::optional<scene::SceneState> s = scene::loadScene(path, error);
  if (!s) return fail(cmd, error);
  const scene::EntityId e = scene::ops::findTerrainEntity(*s, args.get("terrain").value_or(""), error);
  if (e == scene::kNoEntity) return fail(cmd, error);
  const scene::TerrainAsset& t = *scene::terrainOf(*s, e);
  if (out) {
    auto r = terrain::exportHeightmap(t.data->heights(), *out, o);
    if (!r) return fail(cmd, r.error());
    std::printf("wrote %s: %d x %d samples", r->file.c_str(), r->width, r->height);
    if (r->quantisationStep > 0.0)
      std::printf(", heights %.3f..%.3f m in 16 bits (step %.4g m)", double(r->range.min), double(r->range.max),
                  r->quantisationStep);
    if (!r->sidecar.empty()) std::printf(", sidecar %s", r->sidecar.c_str());
    if (r->clampedSamples) std::printf(", %zu samples clamped to the range", r->clampedSamples);
    std::printf("\n");
  }
  if (auto dir = args.get("weights")) {
    auto files = scene::ops::exportPaintWeights(t, *dir, ext, bits);
    if (!files) return fail(cmd, files.error());
    std::printf("wrote %zu paint weight images into %s\n", files->size(), dir->c_str());
  }
  return 0;
}

}  // namespace hs::cli
