#pragma once
// The Stanford bunny the decimation benchmarks measure, imported the way
// they all import it (Z up), so that their tables describe the same mesh.
#include <cstdio>
#include <optional>
#include <string>

#include "mesh/mesh_import.h"

namespace hs::bench {

inline const std::string kBunnyPath = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

// The mesh at `path`, or nothing after the importer's message on stderr.
inline std::optional<hs::mesh::MeshData> loadBunny(const std::string& path) {
  hs::mesh::ImportOptions io;
  io.up = hs::mesh::UpAxis::Z;
  hs::mesh::ImportResult r = hs::mesh::importMesh(path, io);
  if (!r.ok()) {
    std::fprintf(stderr, "%s\n", r.error.c_str());
    return std::nullopt;
  }
  return std::move(*r.mesh);
}

}  // namespace hs::bench
