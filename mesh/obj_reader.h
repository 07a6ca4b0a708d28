#pragma once
// Wavefront OBJ reader: the (memory-mapped) text is read in chunks by all
// cores (obj_reader.cpp says how), coordinates parsed as double and stored
// relative to a double origin, every problem reported with file name and
// line number; results do not depend on the number of threads.
#include <string>
#include <string_view>

#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

// Parses `text` (the whole file). `name` is used in messages, `baseDir` to
// find .mtl files and textures. Returns false with `error` set on a fatal
// problem (malformed statement, truncated file, no faces, cancelled).
// `releaseInput`: `text` is a private file mapping whose pages may be
// dropped once read (keeps peak memory near the mesh's own size); never
// set it for text in ordinary memory.
bool readObj(std::string_view text, const std::string& name, const std::string& baseDir,
             const ImportOptions& options, const Progress* progress, MeshData& out,
             ImportReport& report, std::string& error, bool releaseInput = false);

}  // namespace hs::mesh
