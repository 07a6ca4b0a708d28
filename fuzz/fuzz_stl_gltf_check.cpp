// The STL and GLB checks that run before Assimp (mesh/declared_counts.h).
// The first byte picks which; external glTF buffers resolve against a
// directory that does not exist.
#include <string_view>

#include "fuzz_target.h"
#include "mesh/declared_counts.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const hs::mesh::ByteSource source(std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1), "fuzz");
  hs::mesh::DeclaredCounts declared;
  std::string error;
  if (data[0] & 1) hs::mesh::checkStl(source, declared, error);
  else hs::mesh::checkGltf(source, (data[0] & 2) == 0, "/nonexistent-fuzz-dir", declared, error);
  return 0;
}
