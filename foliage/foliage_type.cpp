// Foliage types: the declarations (core/params.h), validation, clamping and
// JSON, all driven by one table binding each declared key to its field.
#include "foliage/foliage_type.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace hs::foliage {

namespace {

std::vector<double> pair(const glm::dvec2& v) { return {v.x, v.y}; }

// One declared key and the field it reads and writes.
struct Binding {
  std::string key;
  std::function<Json(const FoliageType&)> get;
  std::function<void(FoliageType&, const Json&)> set;
};

glm::dvec2 toPair(const Json& j) { return {j[0].get<double>(), j[1].get<double>()}; }

const std::vector<Binding>& bindings() {
  static const std::vector<Binding> b = {
      {"density_per_ha", [](const FoliageType& t) { return Json(t.densityPerHa); },
       [](FoliageType& t, const Json& j) { t.densityPerHa = j.get<double>(); }},
      {"spacing_m", [](const FoliageType& t) { return Json(t.spacing); },
       [](FoliageType& t, const Json& j) { t.spacing = j.get<double>(); }},
      {"scale_mode", [](const FoliageType& t) { return Json(scaleModeName(t.scaleMode)); },
       [](FoliageType& t, const Json& j) { t.scaleMode = j.get<std::string>() == "xy_z" ? ScaleMode::XyZ : ScaleMode::Uniform; }},
      {"scale", [](const FoliageType& t) { return Json(pair(t.scale)); },
       [](FoliageType& t, const Json& j) { t.scale = toPair(j); }},
      {"scale_z", [](const FoliageType& t) { return Json(pair(t.scaleZ)); },
       [](FoliageType& t, const Json& j) { t.scaleZ = toPair(j); }},
      {"random_yaw", [](const FoliageType& t) { return Json(t.randomYaw); },
       [](FoliageType& t, const Json& j) { t.randomYaw = j.get<bool>(); }},
      {"random_pitch_deg", [](const FoliageType& t) { return Json(t.randomPitchDeg); },
       [](FoliageType& t, const Json& j) { t.randomPitchDeg = j.get<double>(); }},
      {"align_to_normal", [](const FoliageType& t) { return Json(t.alignToNormal); },
       [](FoliageType& t, const Json& j) { t.alignToNormal = j.get<bool>(); }},
      {"align_max_deg", [](const FoliageType& t) { return Json(t.alignMaxDeg); },
       [](FoliageType& t, const Json& j) { t.alignMaxDeg = j.get<double>(); }},
      {"sink_m", [](const FoliageType& t) { return Json(t.sinkDepth); },
       [](FoliageType& t, const Json& j) { t.sinkDepth = j.get<double>(); }},
      {"slope_deg", [](const FoliageType& t) { return Json(pair(t.slopeDeg)); },
       [](FoliageType& t, const Json& j) { t.slopeDeg = toPair(j); }},
      {"altitude_m", [](const FoliageType& t) { return Json(pair(t.altitude)); },
       [](FoliageType& t, const Json& j) { t.altitude = toPair(j); }},
      {"layer", [](const FoliageType& t) { return Json(t.layer); },
       [](FoliageType& t, const Json& j) { t.layer = j.get<std::string>(); }},
      {"layer_weight", [](const FoliageType& t) { return Json(pair(t.layerWeight)); },
       [](FoliageType& t, const Json& j) { t.layerWeight = toPair(j); }},
      {"surface", [](const FoliageType& t) { return Json(surfaceFilterName(t.surface)); },
       [](FoliageType& t, const Json& j) {
         const std::string s = j.get<std::string>();
         t.surface = s == "terrain" ? SurfaceFilter::Terrain : s == "meshes" ? SurfaceFilter::Meshes : SurfaceFilter::Both;
       }},
      {"cull_distance_m", [](const FoliageType& t) { return Json(t.cullDistance); },
       [](FoliageType& t, const Json& j) { t.cullDistance = j.get<double>(); }},
      {"fade_m", [](const FoliageType& t) { return Json(t.fadeLength); },
       [](FoliageType& t, const Json& j) { t.fadeLength = j.get<double>(); }},
      {"cast_shadows", [](const FoliageType& t) { return Json(t.castShadows); },
       [](FoliageType& t, const Json& j) { t.castShadows = j.get<bool>(); }},
      {"impostor", [](const FoliageType& t) { return Json(t.impostor); },
       [](FoliageType& t, const Json& j) { t.impostor = j.get<bool>(); }},
      {"wind_response", [](const FoliageType& t) { return Json(t.windResponse); },
       [](FoliageType& t, const Json& j) { t.windResponse = j.get<double>(); }},
  };
  return b;
}

std::string context(const FoliageType& t) { return "foliage type \"" + t.name + "\""; }

// checkParam's message with the option name replaced by the key.
std::string keyed(const ParamDecl& p, const std::string& error) {
  const std::string name = paramName(p);
  if (error.rfind(name, 0) == 0) return p.key + error.substr(name.size());
  return p.key + ": " + error;
}

}  // namespace

const char* scaleModeName(ScaleMode m) { return m == ScaleMode::XyZ ? "xy_z" : "uniform"; }
const char* surfaceFilterName(SurfaceFilter s) {
  return s == SurfaceFilter::Terrain ? "terrain" : s == SurfaceFilter::Meshes ? "meshes" : "both";
}

const std::vector<ParamDecl>& foliageTypeParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const FoliageType d;
    const std::string g = "foliage type";
    return std::vector<ParamDecl>{
        {.key = "density_per_ha", .option = "density", .label = "Density", .min = 0.0, .max = kMaxDensityPerHa,
         .defaultValue = d.densityPerHa,
         .help = "instances per hectare where the filters keep the surface (at most 100 per square metre)",
         .valueName = "PER_HA", .editor = true, .decimals = 1, .step = 10.0, .group = g},
        {.key = "spacing_m", .option = "spacing", .label = "Minimum spacing", .unit = Unit::Metres, .min = 0.0,
         .max = 1000.0, .defaultValue = d.spacing,
         .help = "no two instances of this type closer than this (Poisson disk; 0: no minimum)", .valueName = "M",
         .editor = true, .decimals = 2, .step = 0.1, .group = g},
        {.key = "scale_mode", .option = "scale-mode", .label = "Scale mode", .type = ParamType::Choice,
         .defaultValue = "uniform", .choices = {"uniform", "xy_z"},
         .help = "one random scale, or one for width (x, y) and one for height (z)", .editor = true, .group = g},
        {.key = "scale", .option = "scale", .label = "Scale", .min = 0.01, .max = 100.0,
         .defaultValue = Json::array({d.scale.x, d.scale.y}),
         .help = "random scale range (uniform), or the width's range (xy_z)", .valueName = "MIN,MAX", .count = 2,
         .editor = true, .decimals = 3, .step = 0.05, .group = g, .ordered = true},
        {.key = "scale_z", .option = "scale-z", .label = "Height scale", .min = 0.01, .max = 100.0,
         .defaultValue = Json::array({d.scaleZ.x, d.scaleZ.y}), .help = "random height scale range (xy_z only)",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .decimals = 3, .step = 0.05, .group = g,
         .ordered = true},
        {.key = "random_yaw", .option = "random-yaw", .label = "Random yaw", .type = ParamType::Flag,
         .defaultValue = d.randomYaw, .help = "turn each instance by a random angle about its up axis",
         .editor = true, .group = g},
        {.key = "random_pitch_deg", .option = "random-pitch", .label = "Random pitch", .unit = Unit::Degrees,
         .min = 0.0, .max = 180.0, .defaultValue = d.randomPitchDeg,
         .help = "tilt each instance by up to this angle in a random direction", .valueName = "DEG",
         .editor = true, .decimals = 1, .group = g},
        {.key = "align_to_normal", .option = "align", .label = "Align to normal", .type = ParamType::Flag,
         .defaultValue = d.alignToNormal, .help = "tilt the up axis toward the surface normal", .editor = true,
         .group = g},
        {.key = "align_max_deg", .option = "align-max", .label = "Align maximum angle", .unit = Unit::Degrees,
         .min = 0.0, .max = 90.0, .defaultValue = d.alignMaxDeg,
         .help = "tilt toward the normal by at most this angle", .valueName = "DEG", .editor = true,
         .decimals = 1, .group = g},
        {.key = "sink_m", .option = "sink", .label = "Sink depth", .unit = Unit::Metres, .min = -100.0, .max = 100.0,
         .defaultValue = d.sinkDepth, .help = "move each instance this far into the surface along its up axis",
         .valueName = "M", .editor = true, .decimals = 3, .step = 0.05, .group = g},
        {.key = "slope_deg", .option = "slope", .label = "Slope range", .unit = Unit::Degrees, .min = 0.0,
         .max = 90.0, .defaultValue = Json::array({d.slopeDeg.x, d.slopeDeg.y}),
         .help = "place only where the surface's slope is within (inclusive)", .valueName = "MIN,MAX", .count = 2,
         .editor = true, .decimals = 2, .group = g, .ordered = true},
        {.key = "altitude_m", .option = "altitude", .label = "Altitude range", .unit = Unit::Metres,
         .min = -100000.0, .max = 100000.0, .defaultValue = Json::array({d.altitude.x, d.altitude.y}),
         .help = "place only where the surface's world Z is within (inclusive)", .valueName = "MIN,MAX",
         .count = 2, .editor = true, .decimals = 2, .group = g, .ordered = true},
        {.key = "layer", .option = "layer", .label = "Paint layer", .type = ParamType::Text, .defaultValue = "",
         .help = "place on the terrain only where this paint layer (material name) weighs within the weight range",
         .valueName = "NAME", .editor = true, .group = g},
        {.key = "layer_weight", .option = "layer-weight", .label = "Layer weight range", .min = 0.0, .max = 1.0,
         .defaultValue = Json::array({d.layerWeight.x, d.layerWeight.y}),
         .help = "the paint layer's weight range kept (inclusive)", .valueName = "MIN,MAX", .count = 2,
         .editor = true, .decimals = 4, .step = 0.05, .group = g, .ordered = true},
        {.key = "surface", .option = "on", .label = "Surfaces", .type = ParamType::Choice, .defaultValue = "both",
         .choices = {"terrain", "meshes", "both"}, .help = "place on terrains, on mesh surfaces (scans) or both",
         .editor = true, .group = g},
        {.key = "cull_distance_m", .option = "cull", .label = "Cull distance", .unit = Unit::Metres, .min = 0.0,
         .max = 100000.0, .defaultValue = d.cullDistance, .help = "not drawn beyond this distance (0: never culled)",
         .valueName = "M", .editor = true, .decimals = 1, .step = 10.0, .group = g},
        {.key = "fade_m", .option = "fade", .label = "Fade length", .unit = Unit::Metres, .min = 0.0,
         .max = 100000.0, .defaultValue = d.fadeLength,
         .help = "fades out over this distance before the cull distance", .valueName = "M", .editor = true,
         .decimals = 1, .step = 5.0, .group = g},
        {.key = "cast_shadows", .option = "shadows", .label = "Cast shadows", .type = ParamType::Flag,
         .defaultValue = d.castShadows, .help = "draw into shadow maps", .editor = true, .group = g},
        {.key = "impostor", .option = "impostor", .label = "Far impostor", .type = ParamType::Flag,
         .defaultValue = d.impostor,
         .help = "beyond its last mesh level, draw it as an octahedral impostor (one card from baked views)",
         .editor = true, .group = g},
        {.key = "wind_response", .option = "wind", .label = "Wind response", .min = 0.0, .max = 10.0,
         .defaultValue = d.windResponse, .help = "how much the wind sways it (0: a rock, 1: a tree)",
         .valueName = "W", .editor = true, .decimals = 2, .step = 0.1, .group = g},
    };
  }();
  return decls;
}

std::vector<std::string> validate(const FoliageType& t) {
  std::vector<std::string> errors;
  const std::string ctx = context(t);
  if (t.name.empty()) errors.push_back("foliage type: name: a type needs a name");
  if (t.mesh.empty()) errors.push_back(ctx + ": mesh: no mesh asset given (every type draws a mesh)");
  for (const Binding& b : bindings()) {
    const ParamDecl& p = paramIn(foliageTypeParamDecls(), b.key);
    std::string error;
    if (!checkParam(p, b.get(t), error)) errors.push_back(ctx + ": " + keyed(p, error));
  }
  if (t.cullDistance > 0.0 && t.fadeLength > t.cullDistance)
    errors.push_back(ctx + ": fade_m: " + formatNumber(t.fadeLength) + " is longer than cull_distance_m " +
                     formatNumber(t.cullDistance));
  return errors;
}

FoliageType sanitized(const FoliageType& t, std::vector<std::string>& warnings) {
  FoliageType s = t;
  const std::string ctx = context(t);
  const auto& d = foliageTypeParamDecls();
  auto one = [&](const char* key, double& v) { v = clampParam(paramIn(d, key), v, warnings, ctx); };
  auto two = [&](const char* key, glm::dvec2& v) {
    one(key, v.x);
    one(key, v.y);
    if (v.y < v.x) {
      warnings.push_back(ctx + ": " + paramIn(d, key).label + " " + formatNumber(v.x) + "," + formatNumber(v.y) +
                         " is not in order; swapped");
      std::swap(v.x, v.y);
    }
  };
  one("density_per_ha", s.densityPerHa);
  one("spacing_m", s.spacing);
  two("scale", s.scale);
  two("scale_z", s.scaleZ);
  one("random_pitch_deg", s.randomPitchDeg);
  one("align_max_deg", s.alignMaxDeg);
  one("sink_m", s.sinkDepth);
  two("slope_deg", s.slopeDeg);
  two("altitude_m", s.altitude);
  two("layer_weight", s.layerWeight);
  one("cull_distance_m", s.cullDistance);
  one("fade_m", s.fadeLength);
  one("wind_response", s.windResponse);
  if (s.cullDistance > 0.0 && s.fadeLength > s.cullDistance) {
    warnings.push_back(ctx + ": fade length " + formatNumber(s.fadeLength) + " is longer than the cull distance; using " +
                       formatNumber(s.cullDistance));
    s.fadeLength = s.cullDistance;
  }
  return s;
}

Json toJson(const FoliageType& t) {
  Json j = Json::object();
  j["name"] = t.name;
  j["mesh"] = t.mesh;
  for (const Binding& b : bindings()) j[b.key] = b.get(t);
  return j;
}

bool fromJson(const Json& j, FoliageType& out, std::string& error, const std::string& path) {
  JsonReader r(error);
  if (!r.object(j, path)) return false;
  FoliageType t;
  if (const Json* n = r.required(j, path, "name")) {
    if (!r.string(*n, jsonPath(path, "name"), t.name)) return false;
  } else {
    return false;
  }
  if (const Json* m = r.required(j, path, "mesh")) {
    if (!r.string(*m, jsonPath(path, "mesh"), t.mesh)) return false;
  } else {
    return false;
  }
  std::set<std::string> known = {"name", "mesh"};
  for (const Binding& b : bindings()) {
    known.insert(b.key);
    const Json* v = JsonReader::member(j, b.key);
    if (!v || v->is_null()) continue;
    const ParamDecl& p = paramIn(foliageTypeParamDecls(), b.key);
    std::string why;
    if (!checkParam(p, *v, why)) {
      std::string what = keyed(p, why);
      what = what.substr(std::min(what.size(), p.key.size() + 2));
      return r.fail(jsonPath(path, b.key), "foliage type \"" + t.name + "\": " + what);
    }
    b.set(t, *v);
  }
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) return r.fail(jsonPath(path, it.key()), "unknown key in a foliage type");
  if (t.cullDistance > 0.0 && t.fadeLength > t.cullDistance)
    return r.fail(jsonPath(path, "fade_m"), "foliage type \"" + t.name + "\": fade " + formatNumber(t.fadeLength) +
                                                " is longer than the cull distance " + formatNumber(t.cullDistance));
  out = std::move(t);
  return true;
}

Json typesToJson(const std::vector<FoliageType>& types) {
  Json arr = Json::array();
  for (const FoliageType& t : types) arr.push_back(toJson(t));
  Json j = Json::object();
  j["types"] = std::move(arr);
  return j;
}

bool typesFromJson(const Json& j, std::vector<FoliageType>& out, std::string& error) {
  JsonReader r(error);
  if (!r.object(j, "")) return false;
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "types") return r.fail(it.key(), "unknown key in the foliage types");
  const Json* arr = r.required(j, "", "types");
  if (!arr || !r.array(*arr, "types")) return false;
  std::vector<FoliageType> types;
  std::set<std::string> names;
  for (size_t i = 0; i < arr->size(); ++i) {
    FoliageType t;
    std::string e;
    if (!fromJson((*arr)[i], t, e, jsonIndex("types", i))) {
      error = e;
      return false;
    }
    if (!names.insert(t.name).second)
      return r.fail(jsonPath(jsonIndex("types", i), "name"), "a second foliage type named \"" + t.name + "\"");
    types.push_back(std::move(t));
  }
  out = std::move(types);
  return true;
}

}  // namespace hs::foliage
