#pragma once
// A foliage type: what one kind of plant or rock is (a mesh asset with its
// LODs) and how it is placed (density, spacing, scale, rotation, filters)
// and drawn (cull distance and fade, shadows, wind). Its parameters are
// declared once (foliageTypeParamDecls(), core/params.h), so the editor's
// panel, the CLI's `foliage type add` options, the file's JSON and `info`
// agree on keys, ranges, units and defaults (docs/foliage.md, "Types").
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/json.h"
#include "core/params.h"

namespace hs::foliage {

enum class ScaleMode : uint8_t {
  Uniform,  // one random factor for x, y and z
  XyZ,      // one factor for x and y (the crown's width), another for z (the height)
};
enum class SurfaceFilter : uint8_t { Terrain, Meshes, Both };

// Density is capped at this many instances per hectare (100 per square
// metre): a 1e9 typed by mistake would ask for 1e5 instances per m^2 and
// exhaust memory on a brush dab; validate() reports the cap.
constexpr double kMaxDensityPerHa = 1e6;

struct FoliageType {
  std::string name = "Foliage";
  std::string mesh;  // the mesh asset (by name) whose LODs draw it; required

  double densityPerHa = 100.0;   // instances per hectare on surfaces the filters keep
  double spacing = 1.0;          // metres: no two instances of this type closer (3D)
  ScaleMode scaleMode = ScaleMode::Uniform;
  glm::dvec2 scale{1.0, 1.0};    // uniform (and XyZ's x and y): min, max
  glm::dvec2 scaleZ{1.0, 1.0};   // XyZ's z: min, max
  bool randomYaw = true;         // uniform yaw in [0, 360)
  double randomPitchDeg = 0.0;   // tilt up to this angle in a random direction
  bool alignToNormal = false;    // tilt the up axis toward the surface normal ...
  double alignMaxDeg = 30.0;     // ... by at most this angle
  double sinkDepth = 0.0;        // metres along the instance's up axis into the surface
  glm::dvec2 slopeDeg{0.0, 90.0};         // surface slope range kept (inclusive)
  glm::dvec2 altitude{-100000.0, 100000.0};  // world Z range kept (inclusive), metres
  std::string layer;                      // paint layer (material name); empty: no layer filter
  glm::dvec2 layerWeight{0.0, 1.0};       // that layer's weight range kept (inclusive)
  SurfaceFilter surface = SurfaceFilter::Both;
  double cullDistance = 1000.0;  // metres: not drawn beyond (0: never culled)
  double fadeLength = 50.0;      // metres before the cull distance over which it fades out
  bool castShadows = true;
  bool impostor = true;          // far instances drawn as an octahedral impostor (the renderer's far level)
  double windResponse = 1.0;     // 0: stiff (a rock); 1: a tree's sway; up to 10

  bool operator==(const FoliageType&) const = default;
};

// The declarations, in the order files and panels list them.
const std::vector<ParamDecl>& foliageTypeParamDecls();

// Messages naming the type and the field ("foliage type \"Pine\":
// density_per_ha: -1 is out of range (0 to 1000000)"); empty: valid.
std::vector<std::string> validate(const FoliageType& t);

// The type clamped into its declared ranges (and min/max pairs put in
// order), with a warning per change naming the type and the field.
FoliageType sanitized(const FoliageType& t, std::vector<std::string>& warnings);

// JSON: {"name": ..., "mesh": ..., <declared keys>}. The reader is strict:
// unknown keys, wrong types and values out of range are errors naming the
// JSON path; a missing declared key takes its default.
Json toJson(const FoliageType& t);
bool fromJson(const Json& j, FoliageType& out, std::string& error, const std::string& path = "");

// A list of types (a scene's): {"types": [...]}; names must be unique.
Json typesToJson(const std::vector<FoliageType>& types);
bool typesFromJson(const Json& j, std::vector<FoliageType>& out, std::string& error);

const char* scaleModeName(ScaleMode m);
const char* surfaceFilterName(SurfaceFilter s);

}  // namespace hs::foliage
