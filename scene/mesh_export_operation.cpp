#include "scene/mesh_export_operation.h"

#include <cstdio>

#include "scene/mesh_target.h"
#include "scene/tileset_export.h"

namespace hs::scene {

const OperationDecl& meshExportOperation() {
  static const OperationDecl op{
      .name = "mesh export",
      .summary = "write a mesh asset or an entity's mesh as OBJ (+ MTL, textures), binary PLY, GLB or 3D Tiles",
      .usage = "<scene.hscene> <asset-or-entity> <out.obj|.ply|.glb|tileset.json> [options]",
      .description =
          "Writes a mesh for other tools. The name is an entity with a mesh (written where the entity places it: "
          "its world transform applied in double) or, if no entity has that name, a mesh asset (as imported). "
          "The format follows the extension (or --format). Without --world, positions are written relative to "
          "the mesh's origin as floats, and the origin goes into <out>_offset.xyz beside the file (import "
          "--origin auto reads it back), for every format. With --world, positions are absolute "
          "(UTM): OBJ writes every digit, PLY writes doubles, GLB puts the origin into its node's translation. "
          "OBJ writes its MTL and textures beside it; PLY keeps the first texture (MeshLab's TextureFile comment) "
          "and no materials, and says so when the mesh has more. 3D Tiles (tileset.json, or --format 3dtiles) "
          "writes the asset, not an entity's placement: its cluster hierarchy as a tile tree of uniform cuts, or "
          "its LOD chain, glb content in tiles/ beside tileset.json, placed on the globe from --crs "
          "(docs/meshes.md).",
      .notes = "Files appear only when complete: a failed export leaves nothing half-written.",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"},
                      {.name = "asset-or-entity", .help = "an entity with a mesh, or a mesh asset"},
                      {.name = "out", .help = "the file to write (.obj, .ply, .glb, or a tileset's .json)"}},
      .params = {
          {.key = "lod", .option = "lod", .label = "LOD level", .unit = Unit::Levels, .min = 0.0, .max = 31.0,
           .integer = true, .defaultValue = 0,
           .help = "the level of detail to write: 0 the imported mesh, K the K-th coarser level", .valueName = "K",
           .editor = true},
          {.key = "world", .option = "world", .label = "World coordinates", .type = ParamType::Flag,
           .defaultValue = false, .help = "write absolute (UTM) positions instead of relative ones and a sidecar"},
          {.key = "format", .option = "format", .label = "Format", .type = ParamType::Choice,
           .defaultValue = "auto", .choices = {"auto", "obj", "ply", "glb", "3dtiles"},
           .help = "the file format (auto: from the extension)", .valueName = "F", .editor = true},
          {.key = "up", .option = "up", .label = "Up axis", .type = ParamType::Choice, .defaultValue = "auto",
           .choices = {"auto", "y", "z"},
           .help = "OBJ and PLY: the file's up axis (auto: Z with --world, as photogrammetry tools write UTM; "
                   "else Y, as DCC tools expect); GLB is always Y up",
           .valueName = "AXIS", .editor = true},
          {.key = "crs", .option = "crs", .label = "Coordinate system", .type = ParamType::Text,
           .defaultValue = "auto",
           .help = "3D Tiles: the coordinate system of the asset's positions, to place the tileset on the globe "
                   "(auto: the one its import recorded, else local; local: unplaced; or EPSG:n / WKT / PROJ)",
           .valueName = "CRS", .editor = true},
          {.key = "draco_bits", .option = "draco-bits", .label = "Draco position bits", .unit = Unit::None,
           .min = 0.0, .max = 30.0, .integer = true, .defaultValue = 0,
           .help = "GLB and 3D Tiles: compress with Draco (KHR_draco_mesh_compression), positions on a grid of "
                   "2^N - 1 steps across each primitive's largest extent (8 to 30; 14: a 6 mm grid over a 100 m "
                   "tile; the largest distance a position moved is reported); 0: no compression, exact",
           .valueName = "N", .editor = true},
      }};
  return op;
}

namespace {

// What Draco's quantization did, measured per position.
std::string dracoNote(int bits, const mesh::ExportResult& r) {
  char text[160];
  std::snprintf(text, sizeof text, "Draco: positions on a %d-bit grid, the largest move %.3g mm", bits,
                r.quantizationError * 1000.0);
  return text;
}

}  // namespace

MeshExportRequest MeshExportRequest::fromParams(const Json& v) {
  MeshExportRequest r;
  if (v.contains("lod")) r.lod = v["lod"].get<int>();
  if (v.contains("world")) r.world = v["world"].get<bool>();
  if (v.contains("format") && v["format"] != "auto") r.format = v["format"].get<std::string>();
  if (v.contains("up")) r.up = v["up"].get<std::string>();
  if (v.contains("crs")) r.crs = v["crs"].get<std::string>();
  if (v.contains("draco_bits")) r.dracoBits = v["draco_bits"].get<int>();
  return r;
}

MeshExportOutcome exportSceneMesh(const SceneState& state, const MeshExportRequest& request,
                                  const Progress* progress) {
  MeshExportOutcome o;
  std::string& error = o.result.error;
  const MeshTarget target = findMeshTarget(state, request.target, error);
  if (!target.asset) return o;
  const MeshAsset* asset = target.asset;
  const glm::dmat4 transform = target.entity != kNoEntity ? state.worldMatrix(target.entity) : glm::dmat4(1.0);
  o.what = target.what;
  const mesh::MeshData* data = asset->data.get();
  if (request.lod > 0) {
    if (request.lod > int(asset->lods.size())) {
      error = "'" + asset->name + "' has " +
              (asset->lods.empty() ? std::string("no LOD levels (only level 0)")
                                   : "LOD levels 0 to " + std::to_string(asset->lods.size())) +
              "; --lod " + std::to_string(request.lod) + " does not exist";
      return o;
    }
    data = asset->lods[size_t(request.lod) - 1].data.get();
    o.what += ", LOD " + std::to_string(request.lod);
  }
  const bool json = request.out.size() >= 5 && request.out.compare(request.out.size() - 5, 5, ".json") == 0;
  if (request.format == "3dtiles" || (request.format.empty() && json)) {
    if (request.lod > 0 || request.world)
      o.result.warnings.push_back("3D Tiles holds every level and its own placement: --lod and --world are not used");
    o.tiles3d = true;
    o.what = "asset '" + asset->name + "'";
    TilesetExportOptions t;
    t.crs = request.crs;
    t.dracoBits = request.dracoBits;
    std::vector<std::string> notes;
    std::vector<std::string> warnings = std::move(o.result.warnings);
    o.result = exportTileset(*asset, request.out, t, notes, progress);
    o.result.warnings.insert(o.result.warnings.begin(), warnings.begin(), warnings.end());
    o.notes = std::move(notes);
    if (o.result.ok() && request.dracoBits > 0) o.notes.push_back(dracoNote(request.dracoBits, o.result));
    return o;
  }
  std::optional<mesh::ExportFormat> format;
  if (request.format == "obj") format = mesh::ExportFormat::Obj;
  else if (request.format == "ply") format = mesh::ExportFormat::Ply;
  else if (request.format == "glb") format = mesh::ExportFormat::Glb;
  else format = mesh::exportFormatFromPath(request.out);
  if (!format) {
    error = request.out + ": unknown mesh format; use .obj, .ply, .glb or a tileset's .json (or --format)";
    return o;
  }
  o.format = *format;
  mesh::ExportOptions options;
  options.format = *format;
  options.transform = transform;
  options.world = request.world;
  options.zUp = request.up == "z" || (request.up == "auto" && request.world);
  options.comment = "from " + o.what;
  if (request.dracoBits > 0 && *format == mesh::ExportFormat::Glb) options.dracoBits = request.dracoBits;
  o.result = mesh::exportMesh(*data, request.out, options, progress);
  if (request.dracoBits > 0 && o.result.ok()) {
    if (options.dracoBits > 0) o.notes.push_back(dracoNote(request.dracoBits, o.result));
    else o.result.warnings.push_back("--draco-bits applies to GLB and 3D Tiles; " + request.out + " was written exact");
  }
  return o;
}

}  // namespace hs::scene
