#pragma once
// Terrain tiles in the .hscene file, as logical blobs of hscene_file.cpp's
// blob table (one per tile, with the tile's content hash in the table's hash
// column, like every blob):
//   terrain/<id>/h/<tx>_<ty>            heights (every tile)
//   terrain/<id>/holes/<tx>_<ty>        holes (only tiles with a hole)
//   terrain/<id>/paint/<layer>/<tx>_<ty> paint weights (only painted tiles)
// A save compares each tile's hash with the file's and writes only tiles
// whose hash differs (after one brush stroke: the few tiles it touched); the
// hashes come from a per-tile cache keyed by revision, so unchanged tiles
// are neither encoded nor re-hashed. A load decodes every tile (its own
// checksum), checks it against the hash column and the description's tile
// summary (terrain_json.h), and names the terrain and the tile of anything
// damaged or missing.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/progress.h"
#include "scene/scene_state.h"
#include "scene/sqlite_db.h"

namespace hs::scene {

// One logical blob a save wants in the file: its content hash and, only if
// the file lacks that content, its bytes.
struct BlobSource {
  std::string hash;
  std::function<std::vector<uint8_t>()> bytes;
  bool terrainTile = false;
  bool foliageCell = false;  // foliage_file.h
  bool clusterPage = false;  // cluster_file.h (a page; an index blob counts as an asset blob)
};

std::string terrainTileKey(TerrainId id, terrain::TileKind kind, int layer, int tileX, int tileY);

// Adds every tile blob of the state's terrains. Call on a snapshot
// (snapshotForSave) when other threads may edit the live terrains.
void addTerrainBlobs(const SceneState& state, std::map<std::string, BlobSource>& out);

// Fills the tiles of the terrains sceneFromJson made, from the blobs table,
// checked against the tile summaries the description gave them.
bool loadTerrainTiles(SqliteDb& db, SceneState& state, const std::string& path, int formatVersion, std::string& error,
                      const Progress* progress);

// A copy of `state` whose terrains are frozen copy-on-write snapshots, for
// saving on a worker thread while the user keeps editing.
SceneState snapshotForSave(const SceneState& state);

}  // namespace hs::scene
