#include "cli/import_request.h"

#include <charconv>
#include <cmath>
#include <filesystem>

#include "mesh/georef_sidecar.h"

namespace hs::cli {
namespace {

bool parseNumber(const std::string& text, double& v) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  return r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(v);
}

// --origin: auto (a sidecar beside each file), none (the file's coordinates),
// x,y,z (by hand), or the path of an offset file.
bool parseOrigin(const std::string& text, mesh::ImportOptions& o, std::string& error) {
  mesh::GeoOffset offset;
  bool isAuto = false, isNone = false;
  std::string why;
  if (mesh::parseGeoOffset(text, offset, isAuto, isNone, why)) {
    if (isAuto) o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Auto;
    else if (isNone) o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::None;
    else {
      o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Manual;
      o.geoOffset = offset.offset;
    }
    return true;
  }
  std::error_code ec;
  if (std::filesystem::is_regular_file(text, ec)) {
    o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::File;
    o.geoOffsetFile = text;
    return true;
  }
  error = "--origin takes auto, none, x,y,z or an offset file (" + why + ")";
  return false;
}

}  // namespace

std::vector<OptionSpec> importOptionSpecs() {
  return {{"at"},          {"up"},   {"reader"}, {"name"},         {"report"}, {"strict-textures", false},
          {"decimate-to"}, {"max-error"}, {"lods"}, {"origin"}, {"clean", false}};
}

bool parseImportRequest(const Args& args, scene::MeshImportRequest& request, std::string& error) {
  mesh::ImportOptions& options = request.import;
  if (auto up = args.get("up")) {
    if (*up == "y") options.up = mesh::UpAxis::Y;
    else if (*up == "z") options.up = mesh::UpAxis::Z;
    else if (*up != "auto") return error = "--up takes auto, y or z", false;
  }
  if (auto r = args.get("reader")) {
    if (*r == "obj") options.reader = mesh::Reader::Obj;
    else if (*r == "assimp") options.reader = mesh::Reader::Assimp;
    else if (*r != "auto") return error = "--reader takes auto, obj or assimp", false;
  }
  options.strictTextures = args.has("strict-textures");
  if (auto origin = args.get("origin"); origin && !parseOrigin(*origin, options, error)) return false;

  mesh::ProcessOptions& p = request.processing;
  if (auto target = args.get("decimate-to")) {
    std::string why;
    if (!mesh::parseDecimateTarget(*target, p.decimation, why)) return error = "--decimate-to: " + why, false;
    p.decimate = true;
  }
  if (auto maxError = args.get("max-error")) {
    double v = 0;
    if (!parseNumber(*maxError, v) || !(v > 0))
      return error = "--max-error takes a distance in metres above 0 (e.g. 0.02), not '" + *maxError + "'", false;
    p.decimation.maxError = v;
    // Alone it decimates as far as the error allows; with --decimate-to,
    // whichever comes first stops it.
    if (!p.decimate) {
      p.decimation.targetRatio = 0.0;
      p.decimation.targetTriangles = 0;
    }
    p.decimate = true;
  }
  if (auto lods = args.get("lods")) {
    double v = -1;
    if (!parseNumber(*lods, v) || v < 0 || v > 8 || v != std::floor(v))
      return error = "--lods takes a whole number of levels from 0 to 8, not '" + *lods + "'", false;
    p.lodLevels = int(v);
  }
  request.process = p.decimate || p.lodLevels > 0 || args.has("clean");
  return true;
}

}  // namespace hs::cli
