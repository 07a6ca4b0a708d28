#pragma once
// The JSON sidecar beside a RAW .r16 heightmap (<file>.r16.json), which
// RAW itself has no room for: the size, the heights 0 and 65535 stand for,
// spacing, origin, CRS, and the Z scale in percent that makes Unreal's
// landscape import reproduce the range (it maps 0..65535 to -256..+256 cm
// times scale / 100). Written and read through hs::Json (core/json.h):
//
//   {"format": "r16", "byte_order": "little_endian", "row_order": "north_first",
//    "width": 1025, "height": 1025, "height_min": 312.5, "height_max": 1480.25,
//    "spacing_x": 2.0, "spacing_y": 2.0, "origin_x": ..., "origin_y": ..., "origin_z": ...,
//    "unreal_z_scale_percent": 228.1, "crs_wkt": "PROJCS[...]"}
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace hs::terrain {

struct RawSidecar {
  int width = 0, height = 0;
  double heightMin = 0.0, heightMax = 1.0;  // what 0 and 65535 stand for, metres
  glm::dvec2 spacing{1.0};
  glm::dvec3 origin{0.0};
  std::string crsWkt;  // empty: no CRS
};

// Writes `sidecar` to `path`; false with `error` naming the file.
bool writeRawSidecar(const std::string& path, const RawSidecar& sidecar, std::string& error);

// Reads the sidecar at `path`. nullopt with `error` naming the file and the
// place when it is not JSON or a member is of the wrong kind
// ("h.r16.json: width (line 5, column 12): expected a whole number ...").
// Members it lacks keep their defaults; width and height are required.
std::optional<RawSidecar> readRawSidecar(const std::string& path, std::string& error);

}  // namespace hs::terrain
