#include "scene/light_add_operation.h"

#include "sequencer/camera_path.h"

namespace hs::scene {
namespace {

ParamDecl vec3Param(const char* key, const char* label, double lo, double hi, const char* help, const char* valueName,
                    Unit unit = Unit::None) {
  return {.key = key, .option = key, .label = label, .type = ParamType::Number, .unit = unit, .min = lo, .max = hi,
          .help = help, .valueName = valueName, .count = 3};
}

ParamDecl numberParam(const char* key, const char* label, double lo, double hi, const char* help, const char* valueName,
                      Unit unit = Unit::None) {
  return {.key = key, .option = key, .label = label, .type = ParamType::Number, .unit = unit, .min = lo, .max = hi,
          .help = help, .valueName = valueName};
}

}  // namespace

const OperationDecl& lightAddOperation() {
  static const OperationDecl op = [] {
    ParamDecl type{.key = "type", .option = "type", .label = "Type", .type = ParamType::Choice,
                   .choices = {"sun", "point", "spot"}, .help = "the kind of light", .required = true};
    ParamDecl name{.key = "name", .option = "name", .label = "Name", .type = ParamType::Text,
                   .help = "the entity's name (default: Sun, Point Light, Spot Light)", .valueName = "NAME"};
    // Ranges as scene/fields.cpp declares the light's fields.
    return OperationDecl{
        .name = "light add",
        .summary = "add a sun, point or spot light",
        .usage = "<scene.hscene> --type sun|point|spot [options]",
        .description = "Adds a light entity (an undoable edit, as the editor's Create menu makes) and saves. "
                       "Intensities are physical: a sun's in lux, a point or spot light's in lumens "
                       "(docs/rendering.md, \"Lights and exposure\").",
        .notes = "Example: hybridscape-cli light add scene.hscene --type spot --at 0,-4,5 --aim 0,0,1 "
                 "--intensity 1500000 --outer 40",
        .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
        .params = {type, name,
                   vec3Param("at", "Location", -1e7, 1e7, "where the light stands (default 0,0,20 for a sun, else 0,0,3)",
                             "X,Y,Z", Unit::Metres),
                   vec3Param("aim", "Aim at", -1e7, 1e7,
                             "a point the sun or spot shines towards (default: straight down)", "X,Y,Z", Unit::Metres),
                   vec3Param("colour", "Colour", 0.0, 1000.0, "linear RGB (default 1,0.96,0.9)", "R,G,B"),
                   numberParam("intensity", "Intensity", 0.0, 1e12,
                               "lux for a sun, lumens for a point or spot light (default 100000 lux, 1500000 lm)", "V"),
                   numberParam("range", "Range", 0.01, 1e7, "point and spot: where the light fades to 0 (default 25)",
                               "M", Unit::Metres),
                   numberParam("inner", "Inner cone", 0.1, 179.9, "spot: full angle of the undimmed beam (default 30)",
                               "DEG", Unit::Degrees),
                   numberParam("outer", "Outer cone", 0.1, 179.9, "spot: full angle where the beam ends (default 45)",
                               "DEG", Unit::Degrees),
                   {.key = "shadows", .option = "shadows", .label = "Casts shadows", .type = ParamType::Flag,
                    .help = "a point or spot light casts shadows (a sun always does; `set` turns it off)"}}};
  }();
  return op;
}

std::optional<LightAddRequest> lightAddRequest(const Json& values, std::string& error) {
  auto has = [&](const char* k) { return values.contains(k) && !values[k].is_null(); };
  auto vec = [&](const char* k) {
    const Json& v = values[k];
    return glm::dvec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  };
  LightAddRequest r;
  const std::string type = has("type") ? values["type"].get<std::string>() : std::string("sun");
  r.light.type = type == "spot" ? Light::Type::Spot : type == "point" ? Light::Type::Point : Light::Type::Sun;
  const bool sun = r.light.type == Light::Type::Sun;
  if (!sun) {
    // Lumens that read in the daylight exposure: a point light gives the
    // sun's 100 000 lux about a metre away, a 45° spot 5 m away.
    r.light.intensity = 1.5e6f;
    r.light.range = 25.0f;
  }
  if (has("name")) r.name = values["name"].get<std::string>();
  if (r.name.empty()) r.name = sun ? "Sun" : r.light.type == Light::Type::Point ? "Point Light" : "Spot Light";
  r.transform.translation = has("at") ? vec("at") : glm::dvec3(0.0, 0.0, sun ? 20.0 : 3.0);
  if (has("aim")) {
    const glm::dvec3 dir = vec("aim") - r.transform.translation;
    if (glm::length(dir) < 1e-9) {
      error = "--aim must differ from --at";
      return std::nullopt;
    }
    r.transform.rotation = sequencer::lookRotation(dir);  // local −Z towards the aim, as a camera looks
  }
  if (has("colour")) r.light.color = glm::vec3(vec("colour"));
  if (has("intensity")) r.light.intensity = float(values["intensity"].get<double>());
  if (has("range")) r.light.range = float(values["range"].get<double>());
  // One cone given alone moves the other's default out of its way; both
  // given must be in order.
  if (has("inner") && has("outer") && values["inner"].get<double>() > values["outer"].get<double>()) {
    error = "--inner " + formatNumber(values["inner"].get<double>()) + " must not exceed --outer " +
            formatNumber(values["outer"].get<double>()) + " degrees";
    return std::nullopt;
  }
  if (has("inner")) r.light.innerConeDeg = float(values["inner"].get<double>());
  if (has("outer")) r.light.outerConeDeg = float(values["outer"].get<double>());
  if (r.light.innerConeDeg > r.light.outerConeDeg) {
    if (has("inner")) r.light.outerConeDeg = r.light.innerConeDeg;
    else r.light.innerConeDeg = r.light.outerConeDeg;
  }
  // A sun casts by default (as in Blender and Unreal); a point or spot light
  // only when asked, as each costs a shadow map (six for a point light).
  r.light.castsShadows = sun || (has("shadows") && values["shadows"].get<bool>());
  return r;
}

}  // namespace hs::scene
