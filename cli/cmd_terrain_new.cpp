// hybridscape-cli terrain new
#include <cstdio>

#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"

namespace hs::cli {

int runTerrainNew(int argc, char** argv) {
  const char* cmd = "terrain new";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"size"}, {"resolution"}, {"name"}, {"height"}, {"hills", false}, {"seed"}, {"at"},
                                  {"lod-error"}},
                 args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli terrain new <scene.hscene> --size WxH --resolution N [options]\n\n"
        "Adds a terrain and an entity showing it (one undo step in the editor), then\n"
        "saves the scene.\n\n"
        "  --size WxH        extent in metres, first to last sample (e.g. 2000x2000)\n"
        "  --resolution N    samples per side, 2..8193 (N or WxH, e.g. 2049); spacing = size / (N-1)\n"
        "  --name NAME       entity and terrain name (default Terrain)\n"
        "  --height MIN,MAX  height range in metres (default 0,100); flat at MIN\n"
        "  --hills           start from fractal hills spanning the height range\n"
        "  --seed N          seed of the hills (default 1)\n"
        "  --at x,y,z        world position of the terrain's centre (default 0,0,0)\n"
        "  --lod-error PX    screen-space error bound of the LOD in pixels (default 1)\n");
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const std::string path = args.positional[0];
  scene::ops::NewTerrain spec;
  if (!args.get("size")) return usage(cmd, "--size WxH (metres) is required");
  if (!args.get("resolution")) return usage(cmd, "--resolution N (samples per side) is required");
  if (!terrain_cli::parseMetres(*args.get("size"), spec.sizeMetres.x, spec.sizeMetres.y, error)) return usage(cmd, error);
  if (!terrain_cli::parseSamples(*args.get("resolution"), spec.samplesX, spec.samplesY, error)) return usage(cmd, error);
  if (auto n = args.get("name")) spec.name = *n;
  if (spec.name.empty()) return usage(cmd, "--name must not be empty");
  if (auto h = args.get("height")) {
    double lo, hi;
    if (!terrain_cli::parsePair(*h, lo, hi, error) || lo > hi) return usage(cmd, "--height takes MIN,MAX with MIN <= MAX");
    spec.heightRange = {float(lo), float(hi)};
  }
  if (args.has("hills")) spec.start = scene::ops::NewTerrain::Start::Hills;
  int seed = 1;
  if (!terrain_cli::intOption(args, "seed", 0, 2147483647, seed, error)) return usage(cmd, error);
  spec.seed = uint64_t(seed);
  if (auto at = args.get("at")) {
    double v[3];
    if (!parseVec3(*at, v, error)) return usage(cmd, "--at: " + error);
    spec.centre = glm::dvec3(v[0], v[1], v[2]);
  }
  if (!terrain_cli::doubleOption(args, "lod-error", 0.1, 64.0, spec.lodErrorPixels, error)) return usage(cmd, error);

  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return fail(cmd, error);
  if (doc.state().findByName(spec.name) != scene::kNoEntity)
    return fail(cmd, "the scene already has an entity named '" + spec.name + "' (choose another with --name)");
  const scene::EntityId id = scene::ops::addTerrain(doc, spec, error);
  if (id == scene::kNoEntity) return fail(cmd, error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return fail(cmd, error);
  const scene::TerrainAsset* t = scene::terrainOf(doc.state(), id);
  const auto& hf = t->data->heights();
  std::printf("added terrain '%s': %d x %d samples, %.3f x %.3f m (spacing %.4f x %.4f m), heights %.2f..%.2f m\n%s\n",
              spec.name.c_str(), hf.samplesX(), hf.samplesY(), hf.sizeMetres().x, hf.sizeMetres().y, hf.spacing().x,
              hf.spacing().y, double(hf.range().min), double(hf.range().max), saved.c_str());
  return 0;
}

}  // namespace hs::cli
