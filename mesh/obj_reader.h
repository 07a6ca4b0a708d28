#pragma once
// Wavefront OBJ reader: the file is read in chunks by all cores
// (obj_reader.cpp says how), coordinates parsed as double and stored
// relative to a double origin, every problem reported with file name and
// line number; results do not depend on the number of threads.
#include <string>

#include "mesh/byte_source.h"
#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

// Parses the whole of `source` (a file, or text in memory); its name is
// used in messages, `baseDir` to find .mtl files and textures. Returns
// false with `error` set on a fatal problem (malformed statement, truncated
// file, a file that changed while it was read, no faces, cancelled).
bool readObj(const ByteSource& source, const std::string& baseDir, const ImportOptions& options,
             const Progress* progress, MeshData& out, ImportReport& report, std::string& error);

}  // namespace hs::mesh
