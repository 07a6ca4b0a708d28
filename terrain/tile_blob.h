#pragma once
// Tile <-> bytes, for the .hscene file (DESIGN.md: terrain tiles are blobs
// keyed by tile, and a save writes only the tiles that changed).
//
// Blob layout (little endian):
//   "HSTT" | u16 version=1 | u8 kind | u8 flags | u16 tileSize=128 | u16 0
//   | u32 tile index | u32 layer | u32 payload bytes | u64 FNV-1a of payload
//   | payload
// flags bit 0: uniform (payload is one sample: a flat or empty tile is ~40 bytes)
// flags bit 1: byte-plane shuffled + deflate (a zlib stream, through libdeflate)
// A decoder checks every field and the checksum, so a damaged blob is an
// error that names the tile, never a half-loaded terrain.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "terrain/result.h"
#include "terrain/terrain.h"

namespace hs::terrain {

enum class TileKind : uint8_t { Height = 1, Holes = 2, Paint = 3 };

std::vector<uint8_t> encodeHeightTile(const Heightfield& hf, int tile);
std::vector<uint8_t> encodeHolesTile(const Heightfield& hf, int tile);
std::vector<uint8_t> encodePaintTile(const PaintLayers& paint, int layer, int tile);
// Decodes a blob into the tile (and layer) its header names; refreshes bounds.
Status decodeTile(Terrain& terrain, std::span<const uint8_t> blob);

// Blob key suffix for a tile ("height/3_4", "holes/3_4", "paint/2/3_4"); the
// scene prefixes the terrain's id.
std::string tileBlobKey(TileKind kind, int layer, int tileX, int tileY);
uint64_t fnv1a(std::span<const uint8_t> bytes);

// Dirty tracking: remember revisions at save time, ask later what changed.
struct TerrainRevisions {
  uint64_t heights = 0, holes = 0;
  std::vector<uint64_t> paint;  // per layer
};
TerrainRevisions currentRevisions(const Terrain& t);
struct DirtyTiles {
  std::vector<int> heights, holes;
  std::vector<std::pair<int, int>> paint;  // (layer, tile)
  size_t count() const { return heights.size() + holes.size() + paint.size(); }
};
DirtyTiles tilesChangedSince(const Terrain& t, const TerrainRevisions& saved);

}  // namespace hs::terrain
