// The own PLY reader (mesh/ply_reader.h): header, counts against the size,
// every body encoding, face lists, strips and per-face texcoords. Seeded
// from the PLY check's corpus (the same files) plus the reader's tests'
// shapes; textures named in the header resolve against a folder that does
// not exist, so no file outside the input is read.
#include <string_view>

#include "fuzz_target.h"
#include "mesh/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const hs::mesh::ByteSource source(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  hs::mesh::ImportOptions options;
  hs::mesh::MeshData mesh;
  hs::mesh::ImportReport report;
  std::string error;
  hs::mesh::readPly(source, "/nonexistent-fuzz-dir", options, nullptr, mesh, report, error);
  return 0;
}
