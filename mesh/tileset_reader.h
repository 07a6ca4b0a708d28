#pragma once
// OGC 3D Tiles 1.0 / 1.1 tilesets (issue 38 item 5: scans processed in
// RealityCapture, Metashape, OpenDroneMap or Cesium ion come in with their
// levels of detail): the tile tree of a tileset.json, external tilesets it
// names followed, implicit quadtrees and octrees expanded into the tiles
// they stand for (mesh/implicit_tiling.h), each tile's content read (b3dm, glb or glTF, cmpt holding
// those; Draco-compressed or not: mesh/gltf_geometry.h) and placed in the
// tileset's frame: glTF's y up turned z up (asset.gltfUpAxis), b3dm's
// RTC_CENTER and CESIUM_RTC added, the tile transforms applied from the
// root down, all in double. That frame is usually ECEF (EPSG:4978);
// scene/tileset_import.h takes it on to the scene's metres.
//
// The tileset's own problems are warnings naming the file, and what they
// spoil is left out while the rest comes in: a content file that is
// missing or unreadable (the tile is kept, empty, marked contentMissing), a tileset that names
// itself again through external references (not followed a second time),
// a subtree file that is missing or broken (a tile marked contentMissing
// stands for what it would have held),
// a content format that is not geometry (pnts, i3dm, vctr, geom) or not
// known at all. Only a tileset.json that cannot be read, or a tileset
// with no triangles at all, is an error.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/progress.h"

namespace hs::mesh {

struct TilesetTile {
  int parent = -1;             // index into Tileset::tiles; -1: a root
  double geometricError = 0.0; // metres: the error of drawing this tile and not its children
  bool additive = false;       // refine "ADD" (children drawn with it), else "REPLACE"
  std::string content;         // the content file(s) read, for messages; "" when none
  bool contentMissing = false; // it names content that did not come in (missing, unreadable, not triangles)
  std::vector<glm::dvec3> positions;  // the tileset's frame (z up), every transform applied
  std::vector<glm::vec2> uvs;         // one per position, or none
  std::vector<uint32_t> indices;      // triangles
};

struct Tileset {
  std::vector<TilesetTile> tiles;  // parents before their children
  std::string version;             // asset.version of the top tileset
  size_t tilesetFiles = 0;         // tileset.json files read (the top one and external ones)
  size_t contentsDeclared = 0, contentsRead = 0;
  size_t trianglesDeclared = 0;    // what the read contents' primitives declare
  std::vector<std::string> warnings;  // each names the file
};

// False with `error` naming the file when `path` is not a readable tileset
// or holds no triangle; cancelled through `progress` (false, error empty).
bool readTileset(const std::string& path, Tileset& out, std::string& error, const Progress* progress = nullptr);

// A tile's content found while reading the tree, not yet decoded (a
// tileset too large to hold decoded: scene/tileset_import.h's streamed path).
struct TilesetContentRef {
  int tile = -1;             // index into Tileset::tiles
  std::string file;          // the content file
  std::string where;         // the tile's JSON path and tileset file, for messages
  glm::dmat4 world{1.0};     // the tile's transform, from the root down
  std::string upAxis = "Y";  // its tileset's asset.gltfUpAxis
  uint64_t bytes = 0;        // its size on disk
};

// The tile tree alone: external tilesets and implicit subtrees followed as
// readTileset does, each binary or glTF content listed in `contents` (in
// tile order) but not decoded. What can be told without decoding is told
// now: a missing file, a cycle, a point-cloud or unknown format (the tile
// marked contentMissing, a warning). False with `error` when the tileset
// cannot be read or lists no content.
bool readTilesetTree(const std::string& path, Tileset& out, std::vector<TilesetContentRef>& contents,
                     std::string& error, const Progress* progress = nullptr);

// One listed content decoded into `into` (the tileset's frame, as
// readTileset places it); its warnings and counts go to `log`. False when
// nothing came in (said in `log`'s warnings).
bool readTilesetContent(const TilesetContentRef& ref, TilesetTile& into, Tileset& log);

// Whether `path` looks like a 3D Tiles tileset: a .json file whose object
// has "asset" and "root".
bool isTilesetFile(const std::string& path);

}  // namespace hs::mesh
