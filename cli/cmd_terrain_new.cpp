// hybridscape-cli terrain new
#include <cstdio>

#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"

namespace hs::cli {

int runTerrainNew(int argc, char** argv) {
  OperationArgs args(scene::ops::terrainNewOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string path = args.positionals()[0];
  scene::ops::NewTerrain spec;
  const std::vector<double> size = args.numbers("size_m"), samples = args.numbers("samples");
  spec.sizeMetres = {size[0], size[1]};
  spec.samplesX = int(samples[0]);
  spec.samplesY = int(samples[1]);
  spec.name = args.text("name");
  if (spec.name.empty()) return args.usage("--name must not be empty");
  const std::vector<double> height = args.numbers("height_m");  // in order: checked on parsing
  spec.heightRange = {float(height[0]), float(height[1])};
  if (args.flag("hills")) spec.start = scene::ops::NewTerrain::Start::Hills;
  spec.seed = uint64_t(args.integer("seed"));
  const std::vector<double> at = args.numbers("at_m");
  spec.centre = glm::dvec3(at[0], at[1], at[2]);
  spec.lodErrorPixels = args.number("lod_error_px");
  std::string error;

  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  if (doc.state().findByName(spec.name) != scene::kNoEntity)
    return args.fail("the scene already has an entity named '" + spec.name + "' (choose another with --name)");
  const scene::EntityId id = scene::ops::addTerrain(doc, spec, error);
  if (id == scene::kNoEntity) return args.fail(error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return args.fail(error);
  const scene::TerrainAsset* t = scene::terrainOf(doc.state(), id);
  const auto& hf = t->data->heights();
  std::printf("added terrain '%s': %d x %d samples, %.3f x %.3f m (spacing %.4f x %.4f m), heights %.2f..%.2f m\n%s\n",
              spec.name.c_str(), hf.samplesX(), hf.samplesY(), hf.sizeMetres().x, hf.sizeMetres().y, hf.spacing().x,
              hf.spacing().y, double(hf.range().min), double(hf.range().max), saved.c_str());
  return 0;
}

}  // namespace hs::cli
