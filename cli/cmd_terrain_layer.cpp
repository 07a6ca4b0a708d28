// hybridscape-cli terrain layer: a paint layer's material, as the editor's
// Layers editor sets it (scene::ops::setTerrainMaterial, one undo step).
#include <cstdio>
#include <filesystem>

#include "cli/terrain_cli.h"
#include "mesh/texture_decode.h"
#include "scene/terrain_ops.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {
namespace {

void printLayers(const scene::TerrainAsset& t) {
  std::printf("layers of '%s':\n", t.name.c_str());
  for (size_t i = 0; i < t.materials.size(); ++i) {
    const terrain::Material& m = t.materials[i];
    std::printf("  %zu. %s: albedo %.3f,%.3f,%.3f, roughness %.2f, tiling %.2f m", i, m.name.c_str(),
                double(m.albedo.r), double(m.albedo.g), double(m.albedo.b), double(m.roughness),
                double(m.tilingMetres));
    if (!m.albedoTexture.empty()) std::printf(", texture %s", m.albedoTexture.c_str());
    if (!m.normalTexture.empty()) std::printf(", normal map %s", m.normalTexture.c_str());
    std::printf("\n");
  }
}

// "none" clears; otherwise the file must decode as an image (the renderer
// would only say so when it draws), and is kept by absolute path so the
// scene opens from any directory.
bool imageFile(const OperationArgs& args, const char* key, std::string& out, std::string& error) {
  const std::string given = args.text(key);
  if (given == "none") {
    out.clear();
    return true;
  }
  mesh::Texture t;
  if (!mesh::decodeTextureFile(given, t, error)) {
    error = "--" + args.operation().param(key).option + " " + error;
    return false;
  }
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(given, ec);
  out = ec ? given : abs.lexically_normal().string();
  return true;
}

}  // namespace

int runTerrainLayer(int argc, char** argv) {
  OperationArgs args(terrain::terrainLayerOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string path = args.positionals()[0];
  std::string error;
  scene::Document doc;
  const scene::TerrainId id = terrain_cli::openTerrain(path, args.text("terrain"), doc, error);
  if (id == scene::kNoTerrain) return args.fail(error);
  const scene::TerrainAsset& asset = *doc.state().findTerrain(id);
  const bool change = args.has("name") || args.has("albedo") || args.has("albedo_texture") ||
                      args.has("normal_map") || args.has("roughness") || args.has("tiling_m");
  if (!change) {
    printLayers(asset);
    return 0;
  }
  if (!args.has("layer")) return args.usage("--layer N says which layer to change");
  const int layer = int(args.integer("layer"));
  if (layer >= int(asset.materials.size()))
    return args.fail("terrain '" + asset.name + "' has " + std::to_string(asset.materials.size()) +
                     " layers (0.." + std::to_string(asset.materials.size() - 1) + "), not " + std::to_string(layer));
  terrain::Material m = asset.materials[size_t(layer)];
  if (args.has("name")) {
    m.name = args.text("name");
    if (m.name.empty()) return args.usage("--name must not be empty");
  }
  if (args.has("albedo")) {
    const std::vector<double> c = args.numbers("albedo");
    m.albedo = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
  }
  if (args.has("albedo_texture") && !imageFile(args, "albedo_texture", m.albedoTexture, error)) return args.fail(error);
  if (args.has("normal_map") && !imageFile(args, "normal_map", m.normalTexture, error)) return args.fail(error);
  if (args.has("roughness")) m.roughness = float(args.number("roughness"));
  if (args.has("tiling_m")) m.tilingMetres = float(args.number("tiling_m"));
  if (m == asset.materials[size_t(layer)]) {
    printLayers(asset);
    std::printf("layer %d is unchanged; nothing saved\n", layer);
    return 0;
  }
  if (!scene::ops::setTerrainMaterial(doc, id, layer, m)) return args.fail("the layer's material was not changed");
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return args.fail(error);
  printLayers(*doc.state().findTerrain(id));
  std::printf("%s\n", saved.c_str());
  return 0;
}

}  // namespace hs::cli
