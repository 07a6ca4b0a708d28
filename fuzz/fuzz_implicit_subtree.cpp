// A 3D Tiles 1.1 subtree file as mesh/implicit_tiling.h reads it: the input
// is the subtree (binary "subt" or JSON); an external buffer it names reads
// back the same input, so offsets and lengths into both are exercised. Every
// index the scheme allows is then looked up, as the tileset reader's walk
// would, to prove the checked sizes cover them.
#include <string>
#include <vector>

#include "fuzz_target.h"
#include "mesh/implicit_tiling.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace hs::mesh;
  const std::vector<uint8_t> bytes(data, data + size);
  ImplicitScheme scheme;
  scheme.dims = 2;
  scheme.subtreeLevels = 3;
  scheme.availableLevels = 6;
  const ReadFile readBack = [&](const std::filesystem::path&, std::vector<uint8_t>& out, std::string&) {
    out = bytes;
    return true;
  };
  Subtree sub;
  std::string problem;
  if (!readSubtree("fuzz.subtree", bytes, scheme, 2, readBack, sub, problem)) return 0;
  unsigned any = 0;
  for (uint64_t i = 0; i < levelOffset(scheme.dims, scheme.subtreeLevels); ++i) {
    any += sub.tiles.at(i);
    for (const Availability& c : sub.contents) any += c.at(i);
  }
  for (uint64_t i = 0; i < (uint64_t(1) << (scheme.dims * scheme.subtreeLevels)); ++i) any += sub.childSubtrees.at(i);
  return any > ~0u ? 1 : 0;
}
