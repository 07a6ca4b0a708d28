#include "particles/particle_operations.h"

#include "core/world_extent.h"

namespace hs::particles {

const OperationDecl& particlesAddOperation() {
  static const OperationDecl op = [] {
    std::vector<std::string> presets = presetNames();
    OperationDecl o{.name = "particles add",
                    .summary = "add a particle emitter from a preset (snow, fog, torch, campfire, dust)",
                    .usage = "<preset> <scene.hscene> [--name N] [--at x,y,z] [--area x0,y0,x1,y1] [--rate R] [--seed S]",
                    .description = "Adds a preset's emitters as entities (one per emitter; a preset with several, "
                                   "such as the torch's flame and smoke, under a parent entity). One undo step. "
                                   "Their fields are then set with `set EMITTER particles.FIELD VALUE`.",
                    .notes = "Examples:\n"
                             "  particles add snow valley.hscene --area -500,-500,500,500 --at 0,0,300\n"
                             "  particles add torch valley.hscene --name \"Gate torch\" --at 120,310,412",
                    .positionals = {{.name = "preset", .help = "snow, fog, torch, campfire or dust"},
                                    {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
    const double W = kWorldExtentMetres;
    o.params = {
        {.key = "preset", .label = "Preset", .type = ParamType::Choice, .defaultValue = presets.front(),
         .choices = presets, .help = "what the emitters make", .editor = true},
        {.key = "name", .option = "name", .label = "Name", .type = ParamType::Text,
         .help = "the entity's name (default: the preset's: Snow, Torch, ...)", .valueName = "N", .editor = true},
        {.key = "at", .option = "at", .label = "Position", .unit = Unit::Metres, .min = -W, .max = W,
         .help = "world position (snow, fog, dust: the height the area starts from)", .valueName = "X,Y,Z",
         .count = 3, .editor = true},
        {.key = "area", .option = "area", .label = "Area", .unit = Unit::Metres, .min = -W, .max = W,
         .help = "the world rectangle snow, fog and dust cover (x0,y0 south-west, x1,y1 north-east; default 100 m "
                 "around the position)",
         .valueName = "X0,Y0,X1,Y1", .count = 4, .editor = true},
        {.key = "rate", .option = "rate", .label = "Rate", .unit = Unit::PerSecond, .min = 0.0, .max = 1e7,
         .help = "particles per second of the main emitter (the others scale with it; default: the preset's)",
         .valueName = "R", .editor = true},
        {.key = "seed", .option = "seed", .label = "Seed", .min = 0, .max = 2147483647, .integer = true,
         .defaultValue = 1, .help = "the same seed gives the same particles", .valueName = "S", .editor = true},
    };
    return o;
  }();
  return op;
}

PresetOptions presetFromValues(const Json& values) {
  PresetOptions o;
  if (values.contains("name") && values["name"].is_string()) o.name = values["name"].get<std::string>();
  if (values.contains("at") && values["at"].is_array() && values["at"].size() == 3)
    o.at = {values["at"][0].get<double>(), values["at"][1].get<double>(), values["at"][2].get<double>()};
  if (values.contains("area") && values["area"].is_array() && values["area"].size() == 4)
    o.area = glm::dvec4(values["area"][0].get<double>(), values["area"][1].get<double>(),
                        values["area"][2].get<double>(), values["area"][3].get<double>());
  if (values.contains("rate") && values["rate"].is_number()) o.rate = values["rate"].get<double>();
  if (values.contains("seed") && values["seed"].is_number()) o.seed = uint32_t(values["seed"].get<double>());
  return o;
}

}  // namespace hs::particles
