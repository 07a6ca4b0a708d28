#include "cli/import_request.h"

#include <filesystem>

#include "mesh/georef_sidecar.h"

namespace hs::cli {
namespace {

// --origin: auto (a sidecar beside each file), none (the file's coordinates),
// x,y,z (by hand, within the declared offset range), or the path of an
// offset file.
bool parseOrigin(const std::string& text, mesh::ImportOptions& o, std::string& error) {
  mesh::GeoOffset offset;
  bool isAuto = false, isNone = false;
  std::string why;
  if (mesh::parseGeoOffset(text, offset, isAuto, isNone, why)) {
    if (isAuto) o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::Auto;
    else if (isNone) o.geoOffsetMode = mesh::ImportOptions::GeoOffsetMode::None;
    else {
      ParamDecl d = paramIn(mesh::importOptionDecls(), "origin_offset_m");
      d.option = "origin";
      const Json v = Json::array({offset.offset.x, offset.offset.y, offset.offset.z});
      if (!checkParam(d, v, error)) return false;
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

bool parseImportRequest(const OperationArgs& args, scene::MeshImportRequest& request, std::string& error) {
  mesh::ImportOptions& options = request.import;
  const std::string up = args.text("up"), reader = args.text("reader");
  options.up = up == "y" ? mesh::UpAxis::Y : up == "z" ? mesh::UpAxis::Z : mesh::UpAxis::Auto;
  options.reader = reader == "obj" ? mesh::Reader::Obj : reader == "assimp" ? mesh::Reader::Assimp : mesh::Reader::Auto;
  options.strictTextures = args.flag("strict_textures");
  options.strict = args.flag("strict");
  if (args.has("origin") && !parseOrigin(args.text("origin"), options, error)) return false;

  mesh::ProcessOptions& p = request.processing;
  if (args.has("decimate_to")) {
    std::string why;
    if (!mesh::parseDecimateTarget(args.text("decimate_to"), p.decimation, why))
      return error = "--decimate-to: " + why, false;
    p.decimate = true;
  }
  if (args.has("max_error_m")) {
    p.decimation.maxError = args.number("max_error_m");
    // Alone it decimates as far as the error allows; with --decimate-to,
    // whichever comes first stops it.
    if (!p.decimate) {
      p.decimation.targetRatio = 0.0;
      p.decimation.targetTriangles = 0;
    }
    p.decimate = true;
  }
  p.refine = !args.flag("no_refine");
  p.error.certify = args.flag("certify");
  p.lodLevels = int(args.integer("lods"));
  request.process = p.decimate || p.lodLevels > 0 || args.flag("clean");
  const std::string clusters = args.text("clusters");
  request.clusters = scene::clustersMode(clusters);
  request.tilesetCrs = args.text("crs");
  return true;
}

}  // namespace hs::cli
