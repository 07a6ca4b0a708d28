#pragma once
// `mesh export` (hybridscape-cli mesh export, the editor's File > Export
// Mesh): a mesh asset, or the mesh of an entity placed where the entity
// stands, written as OBJ (+ MTL, textures), binary PLY or GLB
// (mesh/mesh_export.h), at any of its LOD levels; or an asset as a 3D
// Tiles tileset (scene/tileset_export.h). Parameters declared once.
#include <string>

#include "core/params.h"
#include "core/progress.h"
#include "mesh/mesh_export.h"
#include "scene/scene_state.h"

namespace hs::scene {

const OperationDecl& meshExportOperation();

struct MeshExportRequest {
  std::string target;  // an entity with a mesh (placed by its world matrix), else a mesh asset, by name
  std::string out;     // the file; its extension gives the format unless `format` is set
  int lod = 0;         // 0: the imported mesh; K: LOD level K
  bool world = false;  // absolute coordinates
  std::string format;  // "obj", "ply", "glb", "3dtiles", or empty: from the extension (.json: 3D Tiles)
  std::string crs = "auto";  // 3D Tiles: the positions' coordinate system (scene/tileset_export.h)
  std::string up = "auto";  // "y", "z", or "auto": Z up with --world (UTM), else Y up
  int dracoBits = 0;        // GLB and 3D Tiles: Draco, positions quantized to this many bits (0: none)
  // The request from an operation's values (keys as declared).
  static MeshExportRequest fromParams(const Json& values);
};

struct MeshExportOutcome {
  mesh::ExportResult result;  // result.error set on failure (names the file or the target)
  std::string what;           // "entity 'Stanford Bunny' (asset 'Stanford Bunny', LOD 1)"
  mesh::ExportFormat format = mesh::ExportFormat::Obj;
  bool tiles3d = false;            // written as a 3D Tiles tileset (format unused)
  std::vector<std::string> notes;  // what was assumed (3D Tiles: where it is placed)
};

MeshExportOutcome exportSceneMesh(const SceneState& state, const MeshExportRequest& request,
                                  const Progress* progress = nullptr);

}  // namespace hs::scene
