#pragma once
// FBX, PLY, glTF, DAE, 3DS, STL and the rest through Assimp. Node transforms
// are applied, materials and (embedded or external) diffuse textures kept.
#include <string>

#include "mesh/mesh_data.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {

bool readWithAssimp(const std::string& path, const ImportOptions& options,
                    const Progress* progress, MeshData& out, ImportReport& report,
                    std::string& error);

// True if Assimp has a reader for this extension (".fbx").
bool assimpSupportsExtension(const std::string& extensionWithDot);

}  // namespace hs::mesh
