#pragma once
// Wavefront OBJ reader: one streaming pass over the (memory-mapped) text,
// coordinates parsed as double and stored relative to a double origin, every
// problem reported with file name and line number.
#include <string>
#include <string_view>

#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

// Parses `text` (the whole file). `name` is used in messages, `baseDir` to
// find .mtl files and textures. Returns false with `error` set on a fatal
// problem (malformed statement, truncated file, no faces, cancelled).
bool readObj(std::string_view text, const std::string& name, const std::string& baseDir,
             const ImportOptions& options, const Progress* progress, MeshData& out,
             ImportReport& report, std::string& error);

}  // namespace hs::mesh
