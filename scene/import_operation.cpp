// `import` declared once: the reader's and the processing options, and where
// the mesh lands. --at is within the world extent (core/world_extent.h).
#include "core/world_extent.h"
#include "scene/import_pipeline.h"

namespace hs::scene {

const OperationDecl& meshImportOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "import",
        .summary = "import a mesh (OBJ, FBX, PLY, glTF, 3D Tiles, ...) into a scene",
        .usage = "<mesh-file> [more tiles ...] <scene.hscene> [options]",
        .description = "Imports a mesh (OBJ, FBX, PLY, glTF/GLB, DAE, 3DS, STL) into an existing scene as a new "
                       "asset and an entity showing it, and saves the scene. Several files are the tiles of one "
                       "scan: they share one origin, their borders are welded and they become one asset. A 3D "
                       "Tiles tileset.json comes in as one asset whose cluster hierarchy is its tile tree.",
        .positionals = {{.name = "mesh-file", .help = "the mesh, or the tiles of one scan", .repeated = true},
                        {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
    o.params = {
        {.key = "at_m", .option = "at", .label = "Place at", .unit = Unit::Metres, .min = -kWorldExtentMetres,
         .max = kWorldExtentMetres,
         .help = "put the centre of the mesh's base here (default: where the file's coordinates put it, e.g. at UTM "
                 "coordinates)",
         .valueName = "x,y,z", .count = 3},
        {.key = "name", .option = "name", .label = "Name", .type = ParamType::Text,
         .help = "entity and asset name (default: the file's base name)", .valueName = "NAME"},
    };
    appendParams(o.params, mesh::importOptionDecls());
    appendParams(o.params, mesh::processOptionDecls());
    o.params.push_back(
        {.key = "clusters", .option = "clusters", .label = "Cluster hierarchy", .type = ParamType::Choice,
         .defaultValue = "auto", .choices = {"auto", "on", "streamed", "off"},
         .help = "build a cluster hierarchy (Nanite-style LOD whose pages stream from the scene file; docs/meshes.md) "
                 "from the result: auto builds one for meshes of " +
                 std::to_string(kClusterAutoTriangles / 1000000) +
                 "M triangles and more, out of core for files of " + std::to_string(kClusterStreamedAutoBytes >> 30) +
                 " GB and more; streamed: out of core (tiles read one at a time and never held together; no "
                 "processing); one material only. A 3D Tiles tileset keeps its own tile tree, except streamed "
                 "(or auto at that size): then its finest tiles are built into a hierarchy here",
         .valueName = "MODE", .editor = true});
    o.params.push_back(
        {.key = "crs", .option = "crs", .label = "Tileset CRS", .type = ParamType::Text, .defaultValue = "auto",
         .help = "3D Tiles: the coordinate system an ECEF tileset is converted to: auto (utm for ECEF, else its own "
                 "frame as metres), utm (the zone of its centre, as `terrain import --crs utm`), local, or EPSG:n / "
                 "WKT / PROJ",
         .valueName = "CRS", .editor = true});
    o.params.push_back({.key = "report", .option = "report", .label = "Report", .type = ParamType::Text,
                        .help = "write the import and processing report as JSON (hausdorff_m, hausdorff_rel, "
                                "mean_m, rms_m, p95_m, ...)",
                        .valueName = "FILE"});
    return o;
  }();
  return op;
}

MeshImportRequest::Clusters clustersMode(const std::string& choice) {
  using Clusters = MeshImportRequest::Clusters;
  return choice == "on" ? Clusters::On : choice == "streamed" ? Clusters::Streamed : choice == "off" ? Clusters::Off
                                                                                                     : Clusters::Auto;
}

}  // namespace hs::scene
