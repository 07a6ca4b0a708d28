// The own OBJ reader on any bytes, from memory (no material library can be
// found: the base directory does not exist), with the import's cleaning.
#include <string_view>

#include "fuzz_target.h"
#include "mesh/mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  hs::mesh::importObjFromMemory(text, "fuzz.obj", "/nonexistent-fuzz-dir");
  return 0;
}
