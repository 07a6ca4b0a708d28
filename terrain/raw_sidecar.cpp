#include "terrain/raw_sidecar.h"

#include <fstream>
#include <sstream>

#include "core/json.h"

namespace hs::terrain {

bool writeRawSidecar(const std::string& path, const RawSidecar& s, std::string& error) {
  Json root = Json::object();
  root["format"] = "r16";
  root["byte_order"] = "little_endian";
  root["row_order"] = "north_first";
  root["width"] = s.width;
  root["height"] = s.height;
  root["height_min"] = s.heightMin;
  root["height_max"] = s.heightMax;
  root["spacing_x"] = s.spacing.x;
  root["spacing_y"] = s.spacing.y;
  root["origin_x"] = s.origin.x;
  root["origin_y"] = s.origin.y;
  root["origin_z"] = s.origin.z;
  root["unreal_z_scale_percent"] = (s.heightMax - s.heightMin) * 100.0 / 512.0;
  if (!s.crsWkt.empty()) root["crs_wkt"] = s.crsWkt;
  std::ofstream f(path, std::ios::binary);
  f << writeJson(root) << "\n";
  if (!f) {
    error = path + ": cannot write the sidecar";
    return false;
  }
  return true;
}

std::optional<RawSidecar> readRawSidecar(const std::string& path, std::string& error) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream text;
  text << f.rdbuf();
  if (!f) {
    error = path + ": cannot read the sidecar";
    return std::nullopt;
  }
  const std::string t = text.str();
  const std::optional<Json> j = parseJson(t, error);
  if (!j) {
    error = path + ": not a JSON sidecar (" + error + ")";
    return std::nullopt;
  }
  std::string readerError;
  JsonReader r(readerError);
  RawSidecar s;
  const Json* w = r.object(*j, "") ? r.required(*j, "", "width") : nullptr;
  const Json* h = w ? r.required(*j, "", "height") : nullptr;
  if (!h || !r.integer(*w, "width", s.width, 0, 1 << 30) || !r.integer(*h, "height", s.height, 0, 1 << 30) ||
      !r.optNumber(*j, "", "height_min", s.heightMin) || !r.optNumber(*j, "", "height_max", s.heightMax) ||
      !r.optNumber(*j, "", "spacing_x", s.spacing.x) || !r.optNumber(*j, "", "spacing_y", s.spacing.y) ||
      !r.optNumber(*j, "", "origin_x", s.origin.x) || !r.optNumber(*j, "", "origin_y", s.origin.y) ||
      !r.optNumber(*j, "", "origin_z", s.origin.z) || !r.optString(*j, "", "crs_wkt", s.crsWkt)) {
    error = path + ": " + jsonErrorIn(t, r);
    return std::nullopt;
  }
  return s;
}

}  // namespace hs::terrain
