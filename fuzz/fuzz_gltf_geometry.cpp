// glTF content as 3D Tiles carries it (mesh/gltf_geometry.h): tinygltf's
// parse, then the accessors and the Draco extension read with every number
// checked. GLB or glTF JSON (told by the bytes); external buffers resolve
// against a directory that does not exist.
#include <vector>

#include "fuzz_target.h"
#include "mesh/gltf_geometry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<uint8_t> bytes(data, data + size);
  hs::mesh::GltfGeometry geometry;
  std::string error;
  hs::mesh::readGltfGeometry(bytes, "/nonexistent-fuzz-dir", "fuzz", geometry, error);
  return 0;
}
