// Mesh blobs as a scene file stores them (scene/mesh_blob.h).
#include "fuzz_target.h"
#include "scene/mesh_blob.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  hs::scene::decodeMesh(data, size, "fuzz blob", error);
  return 0;
}
