// The PLY check that runs before Assimp (mesh/declared_counts.h): header,
// counts against the size, binary and ASCII bodies. The own PLY reader has
// its target beside this one (fuzz_ply.cpp, seeded from the same files).
#include <string_view>

#include "fuzz_target.h"
#include "mesh/declared_counts.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const hs::mesh::ByteSource source(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  hs::mesh::DeclaredCounts declared;
  std::string error;
  hs::mesh::checkPly(source, declared, error);
  return 0;
}
