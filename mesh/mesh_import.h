#pragma once
// Entry point for bringing a mesh file in. Picks the reader by extension
// (our own streaming OBJ reader, Assimp for FBX/PLY/glTF/...), converts the
// up axis, cleans the result and recentres it onto a double origin.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/params.h"
#include "core/progress.h"
#include "mesh/georef_sidecar.h"
#include "mesh/mesh_data.h"

namespace hs::mesh {

enum class UpAxis { Auto, Y, Z };
enum class Reader { Auto, Obj, Assimp };

struct ImportOptions {
  // Auto: the file's own declaration where it has one (FBX UpAxis, glTF is
  // Y-up by specification); otherwise Y-up, the convention of DCC exports.
  // Photogrammetry tools writing UTM coordinates are Z-up: pass Z.
  UpAxis up = UpAxis::Auto;
  Reader reader = Reader::Auto;
  // Keep vertex data small floats around a double origin at the bbox centre.
  bool recenter = true;
  // Textures that fail to load become warnings, not errors (the mesh is
  // still useful); set to make them errors.
  bool strictTextures = false;
  // Fail, rather than warn, when the triangles imported differ from those
  // the file declares (ImportReport::declaredTriangles): a file cut short,
  // faces dropped for bad indices, counts that do not match the data.
  bool strict = false;

  // Georeferencing offset added (in double) to the mesh's origin: the
  // file's coordinates are relative to it (georef_sidecar.h).
  //   None:   the file's coordinates are taken as they are (the default)
  //   Auto:   a sidecar beside the file if there is one (Pix4D, ODM, plain)
  //   File:   read from `geoOffsetFile`
  //   Manual: `geoOffset`, set by hand
  enum class GeoOffsetMode { None, Auto, File, Manual };
  GeoOffsetMode geoOffsetMode = GeoOffsetMode::None;
  std::string geoOffsetFile;
  glm::dvec3 geoOffset{0.0};
};

// ImportOptions' parameters, declared once (`import`, the Import dialog):
// up, reader, origin (auto, none, x,y,z or an offset file: the CLI's
// text), origin_offset_m (an offset set by hand: the dialog's fields, and
// the numbers of --origin x,y,z), strict_textures, strict.
const std::vector<ParamDecl>& importOptionDecls();

struct ImportReport {
  std::string file;
  std::string reader;  // "obj" or "assimp"
  size_t verticesIn = 0, trianglesIn = 0;
  size_t verticesOut = 0, trianglesOut = 0;
  size_t nonFiniteVertices = 0;     // NaN/Inf positions (their faces dropped)
  size_t outOfRangeFaces = 0;       // faces with an index past the vertex count
  size_t degenerateFaces = 0;       // repeated index within one face
  size_t polygonsTriangulated = 0;  // faces with more than 3 corners
  size_t skippedLines = 0;          // unsupported statements (lines, points, ...)
  // What the file declares, to compare with what was imported
  // (trianglesOut): the triangles its faces make (OBJ, PLY face lists),
  // its header's count (binary STL), its facets (ASCII STL), its triangle
  // primitives' accessor counts (glTF). `declaredBy` says where the number
  // comes from ("PLY header: element face 200"); empty when the format
  // declares nothing we read (FBX, DAE, 3DS, OFF), and then no comparison
  // is made.
  size_t declaredTriangles = 0;
  std::string declaredBy;
  bool normalsGenerated = false;
  bool upAxisConverted = false;
  std::vector<std::string> warnings;  // each names the file and place
  double seconds = 0.0;
  // The georeferencing offset that was applied (zero and empty if none).
  glm::dvec3 geoOffset{0.0};
  std::string geoOffsetSource;  // file it came from, or "set by hand"
  std::string geoOffsetCrs;     // coordinate system the sidecar named, if any
};

struct ImportResult {
  std::optional<MeshData> mesh;  // set on success
  ImportReport report;
  std::string error;             // set on failure: names the file and place
  bool cancelled = false;
  bool ok() const { return mesh.has_value(); }
};

// Reads `path`. Never throws; on failure `error` says what and where.
ImportResult importMesh(const std::string& path, const ImportOptions& options = {},
                        const Progress* progress = nullptr);

// Reads an OBJ held in memory (the demo scene's embedded bunny). `name` is
// used in messages; relative material/texture paths resolve against `baseDir`.
ImportResult importObjFromMemory(std::string_view data, const std::string& name,
                                 const std::string& baseDir, const ImportOptions& options = {},
                                 const Progress* progress = nullptr);

// Extensions importMesh accepts, lower case with the dot (".obj", ".fbx", ...).
std::vector<std::string> supportedExtensions();
// A path's extension in lower case with the dot (".ply" for "Scan.PLY");
// what every format choice by extension compares against.
std::string lowerExtension(const std::string& path);

}  // namespace hs::mesh
