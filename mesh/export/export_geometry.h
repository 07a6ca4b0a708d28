#pragma once
// What the format writers share (mesh/mesh_export.h is the interface): the
// geometry placed and turned into the file's axes, textures written beside
// the mesh, and files that appear only when complete.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "mesh/mesh_export.h"

namespace hs::mesh::exporting {

struct Geometry {
  // Positions as the file holds them (world, or relative to `origin`), in
  // the file's axes; double so world coordinates keep every digit.
  std::vector<glm::dvec3> positions;
  std::vector<glm::vec3> normals;  // unit, same count (empty if the mesh has none)
  std::vector<glm::vec2> uvs;      // same count, or empty; MeshData's convention (v down, as glTF; OBJ and PLY flip)
  std::vector<uint32_t> indices;   // counter-clockwise seen from the front after placing
  glm::dvec3 origin{0.0};          // the placed origin in the file's axes
  bool world = false;
};

// `transform` applied in double, normals by its inverse transpose, winding
// reversed when it mirrors; then Z-up to Y-up (x, z, -y) when `yUp`.
Geometry placeGeometry(const MeshData& mesh, const ExportOptions& o, bool yUp);

// A file written under a temporary name beside its final path and renamed
// by commit(); one not committed is removed.
class PendingFiles {
 public:
  PendingFiles() = default;
  PendingFiles(const PendingFiles&) = delete;
  PendingFiles& operator=(const PendingFiles&) = delete;
  ~PendingFiles();
  // Writes `bytes` to a temporary file for `path`; false with `error`.
  bool add(const std::string& path, const std::string& bytes, std::string& error);
  // Renames every temporary to its final name; false with `error` (and
  // nothing of this export left behind) if one fails.
  bool commit(std::vector<std::string>& written, std::string& error);

 private:
  std::vector<std::pair<std::string, std::string>> files_;  // temporary, final
};

// A texture's bytes as a file: its original encoded bytes when it has
// them (extension from their signature: PNG, JPEG, or TIFF unless
// `pngOrJpeg`, glTF's only two), else PNG from its pixels. Empty with
// `error` if neither works.
std::string textureFileBytes(const Texture& t, bool pngOrJpeg, std::string& extension, std::string& error);

// Shortest decimal text that reads back to the same value.
void appendNumber(std::string& out, double v);
void appendNumber(std::string& out, float v);

// The writers: the file's bytes into `files` (the mesh first). False with
// `error`; cancelled through `progress`.
bool writeObj(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error);
bool writePly(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error);
// With `o.dracoBits`, `quantizationError` (if given) receives the largest
// distance a position moved.
bool writeGlb(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error, double* quantizationError = nullptr);

}  // namespace hs::mesh::exporting
