#pragma once
// 3D Tiles 1.1 implicit tiling (and the 1.0 extension it grew from,
// 3DTILES_implicit_tiling): a tile that names a subdivision scheme instead
// of children. Its quadtree or octree is described by subtree files, each
// holding `subtreeLevels` levels as availability bitstreams (which tiles
// exist, which have content, which child subtrees exist), in Morton order
// level by level. This file reads the scheme and subtree files and does the
// index arithmetic; mesh/tileset_reader.cpp walks the tree and reads each
// available tile's content through the same path as explicit tiles.
//
// Written here, not taken from a library: Debian packs no 3D Tiles reader
// (Cesium Native is not packaged), and the format is a few bit arrays.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/json.h"

namespace hs::mesh {

struct ImplicitScheme {
  int dims = 2;              // 2: QUADTREE, 3: OCTREE
  int subtreeLevels = 0;     // levels per subtree file
  int availableLevels = 0;   // levels in the whole tree (the tile's own is level 0)
  std::string subtreeUri;    // template with {level} {x} {y} {z}
};

// The tile's `implicitTiling` (or extensions.3DTILES_implicit_tiling) read
// into `out`. False with `problem` (which field, why) when it is not usable;
// false with `problem` empty when the tile has none.
bool parseImplicitTiling(const Json& tile, ImplicitScheme& out, std::string& problem);

// One availability: a constant, or one bit per index (least significant
// bit first within each byte).
struct Availability {
  bool constant = true;
  bool value = false;
  std::vector<uint8_t> bits;
  bool at(uint64_t i) const { return constant ? value : (bits[size_t(i >> 3)] >> (i & 7)) & 1u; }
};

struct Subtree {
  Availability tiles;                // levelOffset(level) + morton, for each level of the subtree
  std::vector<Availability> contents;  // one per content of the implicit tile, indexed like `tiles`
  Availability childSubtrees;        // morton index at level subtreeLevels below the subtree's root
};

// Reads external subtree buffers: (path, bytes, problem) -> ok.
using ReadFile = std::function<bool(const std::filesystem::path&, std::vector<uint8_t>&, std::string&)>;

// A subtree file (binary "subt", or JSON with external buffers, which are
// read through `readFile` relative to `file`'s folder). `contentCount` is how
// many contents the implicit tile declares. False with `problem` naming
// what is wrong (every offset, length and bitstream size is checked
// against the scheme's tile counts).
bool readSubtree(const std::filesystem::path& file, const std::vector<uint8_t>& bytes, const ImplicitScheme& scheme,
                 size_t contentCount, const ReadFile& readFile, Subtree& out, std::string& problem);

// The number of tiles in levels [0, level) of a subtree: (2^(dims*level) - 1) / (2^dims - 1).
uint64_t levelOffset(int dims, int level);
// The Morton (Z-order) index of (x, y[, z]): x in the lowest bit.
uint64_t mortonIndex(int dims, uint64_t x, uint64_t y, uint64_t z);
// `uri` with {level}, {x}, {y}, {z} replaced.
std::string expandImplicitUri(const std::string& uri, int level, uint64_t x, uint64_t y, uint64_t z);

}  // namespace hs::mesh
