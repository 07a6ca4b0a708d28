#include "mesh/declared_counts.h"

#include <algorithm>
#include <filesystem>

namespace hs::mesh {

bool checkBeforeAssimp(const std::string& path, DeclaredCounts& declared, std::string& error) {
  declared = {};
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".ply" && ext != ".stl" && ext != ".glb" && ext != ".gltf") return true;
  ByteSource source;
  if (!source.open(path, error)) return false;
  if (ext == ".ply") return checkPly(source, declared, error);
  if (ext == ".stl") return checkStl(source, declared, error);
  return checkGltf(source, ext == ".glb", std::filesystem::path(path).parent_path().string(), declared, error);
}

}  // namespace hs::mesh
