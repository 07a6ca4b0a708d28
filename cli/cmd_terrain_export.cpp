// hybridscape-cli terrain export
#include <cstdio>

#include "cli/scene_open.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"
#include "terrain/heightmap_image.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {

int runTerrainExport(int argc, char** argv) {
  OperationArgs args(terrain::terrainExportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const bool hasOut = args.has("out");
  if (!hasOut && !args.has("weights")) return args.usage("--out FILE (and/or --weights DIR) is required");
  const std::string out = args.text("out");
  if (hasOut && !terrain::heightmapFormatFor(out))
    return args.fail(out + ": unknown heightmap type; use .png (16-bit), .exr, .tif (GeoTIFF) or .r16");
  terrain::HeightExportOptions o;
  if (args.has("range_m")) {
    const std::vector<double> r = args.numbers("range_m");
    if (!(r[1] > r[0])) return args.usage("--range takes MIN,MAX with MIN < MAX");
    o.range = terrain::HeightRange{float(r[0]), float(r[1])};
  }
  const std::string format = args.text("weights_format");
  const std::string ext = format == "exr" ? "exr" : "png";
  const int bits = format == "png8" ? 8 : 16;
  std::string error;
  const std::string path = args.positionals()[0];
  std::optional<scene::SceneState> s = openScene(path, error);
  if (!s) return args.fail(error);
  const scene::EntityId e = scene::ops::findTerrainEntity(*s, args.text("terrain"), error);
  if (e == scene::kNoEntity) return args.fail(error);
  const scene::TerrainAsset& t = *scene::terrainOf(*s, e);
  if (hasOut) {
    auto r = terrain::exportHeightmap(t.data->heights(), out, o);
    if (!r) return args.fail(r.error());
    std::printf("wrote %s: %d x %d samples", r->file.c_str(), r->width, r->height);
    if (r->quantisationStep > 0.0)
      std::printf(", heights %.3f..%.3f m in 16 bits (step %.4g m)", double(r->range.min), double(r->range.max),
                  r->quantisationStep);
    if (!r->sidecar.empty()) std::printf(", sidecar %s", r->sidecar.c_str());
    if (r->clampedSamples) std::printf(", %zu samples clamped to the range", r->clampedSamples);
    std::printf("\n");
  }
  if (args.has("weights")) {
    const std::string dir = args.text("weights");
    auto files = scene::ops::exportPaintWeights(t, dir, ext, bits);
    if (!files) return args.fail(files.error());
    std::printf("wrote %zu paint weight images into %s\n", files->size(), dir.c_str());
  }
  return 0;
}

}  // namespace hs::cli
