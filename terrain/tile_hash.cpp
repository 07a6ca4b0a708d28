#include "terrain/tile_hash.h"

#include "core/content_hash.h"

namespace hs::terrain {

uint64_t tileContentHash(TileKind kind, int layer, int tile, const void* data, size_t bytes) {
  // The seed says which tile this is, so equal contents of different tiles
  // hash differently.
  const uint64_t seed = 0x4853545400000000ull ^ (uint64_t(kind) << 40) ^ (uint64_t(uint32_t(layer)) << 20) ^
                        uint64_t(uint32_t(tile));
  return contentHash(data, bytes, seed);
}

}  // namespace hs::terrain
