#include "foliage/foliage_operations.h"

#include <type_traits>

namespace hs::foliage {
namespace {

const PositionalDecl kScene{.name = "scene.hscene", .help = "the scene file (saved afterwards)"};

ParamDecl regionParam() {
  return {.key = "region", .option = "region", .label = "Region", .unit = Unit::Metres, .min = -1e7, .max = 1e7,
          .help = "only within this world rectangle (x0,y0 south-west, x1,y1 north-east)",
          .valueName = "X0,Y0,X1,Y1", .count = 4};
}

ParamDecl seedParam() {
  return {.key = "seed", .option = "seed", .label = "Seed", .min = 0, .max = 2147483647, .integer = true,
          .defaultValue = 1, .help = "the same seed places the same instances with the same ids", .valueName = "S"};
}

// A declaration of the type's without its default: a scatter option that
// overrides the type only when given.
ParamDecl override(const char* key, const char* help) {
  ParamDecl p = paramIn(foliageTypeParamDecls(), key);
  p.defaultValue = nullptr;
  p.help = help;
  p.group.clear();
  return p;
}

glm::dvec2 pairOf(const Json& j) { return {j[0].get<double>(), j[1].get<double>()}; }

}  // namespace

const OperationDecl& foliageTypeAddOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage type add",
                    .summary = "add a foliage type drawing a mesh asset",
                    .usage = "<name> --mesh <asset> <scene.hscene> [options]",
                    .description = "Adds a foliage type: the mesh asset that draws it (with its LODs) and how its "
                                   "instances are placed and drawn. Values outside the ranges below are refused.",
                    .positionals = {{.name = "name", .help = "the type's name (unique in the scene)"}, kScene}};
    o.params.push_back({.key = "mesh", .option = "mesh", .label = "Mesh", .type = ParamType::Text,
                        .help = "the mesh asset that draws the type", .valueName = "ASSET", .required = true,
                        .editor = true});
    appendParams(o.params, foliageTypeParamDecls());
    return o;
  }();
  return op;
}

const OperationDecl& foliageScatterOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage scatter",
                    .summary = "scatter a foliage type by rule over the terrain and meshes",
                    .usage = "<type> <scene.hscene> [options]",
                    .description = "Places instances of a type over the whole scene (or a region) by its rules: "
                                   "Poisson-disk at its spacing, its density, slope, altitude and paint-layer "
                                   "filters; the options below override them for this scatter. One undo step.",
                    .positionals = {{.name = "type", .help = "the foliage type"}, kScene}};
    o.params = {
        override("density_per_ha", "instances per hectare (default: the type's)"),
        regionParam(),
        override("layer", "only where this paint layer weighs within the type's weight range (default: the type's)"),
        override("slope_deg", "slope range kept (default: the type's)"),
        override("altitude_m", "altitude range kept (default: the type's)"),
        override("surface", "terrain, meshes or both (default: the type's)"),
        seedParam(),
    };
    return o;
  }();
  return op;
}

const OperationDecl& foliageFillOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage fill",
                    .summary = "fill a terrain paint layer's region with a foliage type",
                    .usage = "<type> <scene.hscene> --layer <name> [options]",
                    .description = "Paints a type to its density wherever the terrain's paint layer weighs at "
                                   "least the minimum weight (the type's own filters apply too): a forest where "
                                   "the forest layer was painted. Terrain only. One undo step.",
                    .positionals = {{.name = "type", .help = "the foliage type"}, kScene}};
    o.params = {
        {.key = "layer", .option = "layer", .label = "Paint layer", .type = ParamType::Text,
         .help = "the terrain paint layer (its material's name)", .valueName = "NAME", .required = true,
         .editor = true},
        {.key = "min_weight", .option = "min-weight", .label = "Minimum weight", .min = 0.0, .max = 1.0,
         .defaultValue = 0.5, .help = "the layer's weight from which the region counts", .valueName = "W",
         .editor = true},
        regionParam(),
        seedParam(),
    };
    return o;
  }();
  return op;
}

const OperationDecl& foliageClearOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage clear",
                    .summary = "remove a foliage type's instances",
                    .usage = "<type> <scene.hscene> [--region x0,y0,x1,y1]",
                    .description = "Removes every instance of a type (or those in a region). One undo step.",
                    .positionals = {{.name = "type", .help = "the foliage type"}, kScene}};
    o.params = {regionParam()};
    return o;
  }();
  return op;
}

const OperationDecl& foliageMoveOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage move",
                    .summary = "move a foliage type's instances by an exact offset",
                    .usage = "<type> <scene.hscene> --offset dx,dy,dz [--region x0,y0,x1,y1] [--keep-height]",
                    .description = "Moves every instance of a type (or those in a region) by an offset in metres; "
                                   "each is put back on the surface under its new place (the offset's height is "
                                   "then unused) unless --keep-height. Ids stay. One undo step.",
                    .positionals = {{.name = "type", .help = "the foliage type"}, kScene}};
    o.params = {
        {.key = "offset_m", .option = "offset", .label = "Offset", .unit = Unit::Metres, .min = -1e6, .max = 1e6,
         .defaultValue = Json::array({0.0, 0.0, 0.0}), .help = "east, north and up, in metres",
         .valueName = "DX,DY,DZ", .count = 3, .required = true, .editor = true, .decimals = 3, .step = 0.1},
        {.key = "keep_height", .option = "keep-height", .label = "Keep height", .type = ParamType::Flag,
         .help = "move by the offset's height too instead of putting each back on the ground", .editor = true},
        regionParam(),
    };
    return o;
  }();
  return op;
}

const OperationDecl& foliageImpostorsOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage impostors",
                    .summary = "bake the foliage's impostors into the scene",
                    .usage = "<scene.hscene> [--all]",
                    .description = "Bakes the octahedral impostor (the far level) of every mesh a foliage type draws "
                                   "with one, where the scene stores none or a stale one (its mesh or materials "
                                   "changed), and stores them in the scene: it then opens and renders without "
                                   "baking, and every render node draws the same picture. Needs OpenGL. One undo "
                                   "step.",
                    .positionals = {kScene}};
    o.params = {{.key = "all", .option = "all", .label = "All", .type = ParamType::Flag,
                 .help = "bake every one again, current or not", .editor = false}};
    return o;
  }();
  return op;
}

const OperationDecl& foliagePlantOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{.name = "foliage plant",
                    .summary = "generate a plant (tree, shrub, grass, rock) as a mesh asset",
                    .usage = "<name> --kind broadleaf|conifer|shrub|grass|rock <scene.hscene> [options]",
                    .description = "Generates a plant after Weber & Penn (trees), or a shrub, grass clump or rock, "
                                   "with its LODs, as a mesh asset a foliage type can draw. The same seed gives the "
                                   "same plant.",
                    .positionals = {{.name = "name", .help = "the asset's name"}, kScene}};
    o.params = plantParamDecls();
    for (ParamDecl& p : o.params)
      if (p.key == "kind") p.required = true;
    return o;
  }();
  return op;
}

bool typeFromValues(const std::string& name, const Json& values, FoliageType& out, std::string& error) {
  const OperationDecl& op = foliageTypeAddOperation();
  if (!values.is_object()) {
    error = "foliage type add: expected the values as an object";
    return false;
  }
  for (auto it = values.begin(); it != values.end(); ++it) {
    const ParamDecl* p = op.find(it.key());
    if (!p) {
      error = "foliage type add: no option " + it.key();
      return false;
    }
    if (!checkParam(*p, it.value(), error)) return false;
  }
  // Through the type's own strict reader: the declared keys are its keys.
  Json j = values;
  j["name"] = name;
  if (!j.contains("mesh")) j["mesh"] = "";
  if (!fromJson(j, out, error)) return false;
  const std::vector<std::string> problems = validate(out);
  if (!problems.empty()) {
    error = problems.front();
    return false;
  }
  return true;
}

FoliageType scatterRules(const FoliageType& type, const Json& values) {
  FoliageType t = type;
  auto get = [&](const char* k) -> const Json* {
    auto it = values.find(k);
    return it == values.end() || it->is_null() ? nullptr : &*it;
  };
  if (const Json* v = get("density_per_ha")) t.densityPerHa = v->get<double>();
  if (const Json* v = get("layer")) t.layer = v->get<std::string>();
  if (const Json* v = get("slope_deg")) t.slopeDeg = pairOf(*v);
  if (const Json* v = get("altitude_m")) t.altitude = pairOf(*v);
  if (const Json* v = get("surface")) {
    const std::string s = v->get<std::string>();
    t.surface = s == "terrain" ? SurfaceFilter::Terrain : s == "meshes" ? SurfaceFilter::Meshes : SurfaceFilter::Both;
  }
  return t;
}

std::optional<Region2> regionFromValues(const Json& values) {
  auto it = values.find("region");
  if (it == values.end() || !it->is_array() || it->size() != 4) return std::nullopt;
  const Json& r = *it;
  return Region2::rect({r[0].get<double>(), r[1].get<double>()}, {r[2].get<double>(), r[3].get<double>()});
}

PlantParams plantFromValues(const Json& values) {
  PlantKind kind = PlantKind::Broadleaf;
  if (auto it = values.find("kind"); it != values.end() && it->is_string())
    for (int k = 0; k <= int(PlantKind::Rock); ++k)
      if (*it == plantKindName(PlantKind(k))) kind = PlantKind(k);
  PlantParams p = defaultPlant(kind);
  auto num = [&](const char* k, auto& field) {
    if (auto it = values.find(k); it != values.end() && it->is_number()) field = std::remove_reference_t<decltype(field)>(it->template get<double>());
  };
  double seed = double(p.seed);
  num("seed", seed);
  p.seed = uint64_t(seed);
  num("height_m", p.height);
  num("levels", p.levels);
  num("branches", p.branches);
  num("leaf_size_m", p.leafSize);
  num("leaves_per_branch", p.leavesPerBranch);
  num("sides", p.sides);
  return p;
}

}  // namespace hs::foliage
