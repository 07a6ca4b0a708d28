#pragma once
// The content hashes .hscene files before format version 4 stored: a
// word-wise FNV-1a variant for meshes and a multiply-xorshift hash for
// terrain tiles, written by hand before the project hashed with XXH3
// (core/content_hash.h). Kept only so that old files are still checked
// against their own checksums when they are opened; nothing writes them.
#include <cstddef>
#include <cstdint>

#include "mesh/mesh_data.h"
#include "terrain/tile_blob.h"

namespace hs::scene {

// The first format whose hashes are XXH3.
inline constexpr int kFirstXxh3Format = 4;

uint64_t legacyMeshHash(const mesh::MeshData& mesh);
uint64_t legacyTileHash(terrain::TileKind kind, int layer, int tile, const void* data, size_t bytes);

}  // namespace hs::scene
