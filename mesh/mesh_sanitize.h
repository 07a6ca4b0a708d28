#pragma once
// Cleaning that every importer applies before a mesh enters a scene: faces
// that would break rendering or later processing are dropped and counted,
// never silently.
#include <string>

#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

// Drops faces with an out-of-range index, a repeated index, or a corner on a
// NaN/Inf vertex; removes vertices no face uses; keeps submesh ranges right.
// Adds the counts to `report` and a warning (naming `file`) for each kind.
void sanitize(MeshData& mesh, ImportReport& report);

// Puts the whole index range in one submesh if the reader made none.
void ensureSubmesh(MeshData& mesh);

}  // namespace hs::mesh
