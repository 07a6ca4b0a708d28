#pragma once
// A tileset too large to hold decoded (issue 38: memory must not grow with
// the scan): `import tileset.json --clusters streamed`, and auto when its
// contents hold kClusterStreamedAutoBytes or more. The tile tree is read
// without decoding (mesh/tileset_reader.h readTilesetTree), the contents of
// its full detail picked (mesh/tileset_finest.h) and decoded one at a time
// into the out-of-core build (meshproc/cluster_build_streamed.h), each
// converted from ECEF by PROJ as the in-core import does. The tileset's
// own coarser levels are not used: the hierarchy is built here, with
// locked borders (crack-free where the tileset's levels may crack).
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/tileset_reader.h"
#include "scene/import_pipeline.h"

namespace hs::scene {

// `tree` and `contents` as readTilesetTree gave them.
ImportedMesh importTilesetStreamed(const std::string& path, const MeshImportRequest& request, mesh::Tileset tree,
                                   const std::vector<mesh::TilesetContentRef>& contents, const Progress* progress);

}  // namespace hs::scene
