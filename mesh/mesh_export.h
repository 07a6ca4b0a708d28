#pragma once
// Writing a mesh for other tools: OBJ (+ MTL and its textures beside it),
// binary PLY, glTF binary (GLB). The positions written are
//   P = transform * (mesh.origin + local position), in double,
// either as they are (`world`: UTM coordinates; PLY and OBJ keep every
// digit, PLY as doubles; GLB puts the world origin into its node's
// translation, which glTF stores as JSON numbers, i.e. doubles), or
// relative to the mesh's placed origin O = transform * origin, as floats,
// with O (world axes) in a Pix4D-style offset sidecar `<stem>_offset.xyz` beside it
// (mesh/georef_sidecar.h: `import --origin auto` reads it back), for
// every format. glTF is
// Y-up by specification; OBJ and PLY are written Y-up (the convention of
// DCC tools, and what import assumes without --up) unless `zUp`
// (photogrammetry tools' convention).
//
// Files are written under temporary names and renamed when complete, so a
// failed or cancelled export leaves no half-written file behind.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/progress.h"
#include "mesh/mesh_data.h"

namespace hs::mesh {

enum class ExportFormat { Obj, Ply, Glb };

// From the extension: .obj, .ply, .glb; nullopt for anything else.
std::optional<ExportFormat> exportFormatFromPath(const std::string& path);
const char* exportFormatName(ExportFormat f);  // "obj", "ply", "glb"

struct ExportOptions {
  ExportFormat format = ExportFormat::Obj;
  glm::dmat4 transform{1.0};  // where the mesh is placed (an instance's world matrix)
  bool world = false;         // absolute positions, else relative to the placed origin + sidecar
  bool zUp = false;           // OBJ and PLY: keep Z up (glTF is always Y-up)
  std::string comment;        // written into the file's header where the format has one
  // GLB: KHR_draco_mesh_compression with positions quantized to this many
  // bits (8-30; mesh/export/draco_encode.h); 0: plain accessors, exact.
  int dracoBits = 0;
};

struct ExportResult {
  std::string error;                // empty on success; names the file
  std::vector<std::string> warnings;  // what the format could not hold (PLY: materials, textures after the first)
  std::vector<std::string> written; // every file written, the mesh first
  size_t vertices = 0, triangles = 0;
  glm::dvec3 origin{0.0};           // the placed origin (what a sidecar holds)
  double quantizationError = 0.0;   // Draco: the largest distance a position moved, metres (0: exact)
  bool ok() const { return error.empty(); }
};

ExportResult exportMesh(const MeshData& mesh, const std::string& path, const ExportOptions& options,
                        const Progress* progress = nullptr);

}  // namespace hs::mesh
