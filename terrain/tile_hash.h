#pragma once
// Content hash of a tile's samples, for the .hscene file's per-blob hash
// column: a save writes a tile only when its hash differs from the file's,
// and a load checks every decoded tile against it. Hashing the raw samples
// (not the encoded blob) means a tile need not be encoded to learn that it is
// unchanged. XXH3 (core/content_hash.h): a 64 KiB height tile hashes in a
// few microseconds.
#include <cstddef>
#include <cstdint>

#include "terrain/tile_blob.h"

namespace hs::terrain {

// Hash of `bytes` bytes of tile data, seeded with what the tile is (kind,
// layer, index), so equal contents of different tiles hash differently.
uint64_t tileContentHash(TileKind kind, int layer, int tile, const void* data, size_t bytes);

// Combines hashes in order (the per-terrain summary of all tile hashes).
inline uint64_t hashCombine(uint64_t seed, uint64_t h) {
  seed ^= h + 0x9e3779b97f4a7c15ull + (seed << 12) + (seed >> 4);
  return seed;
}

}  // namespace hs::terrain
