#pragma once
// Cluster hierarchies (scene/cluster_asset.h) in the .hscene file, as
// logical blobs of hscene_file.cpp's blob table keyed by content hash:
//   clusters/index/<hash>   an asset's index blob (hash: MeshAsset::clustersHash)
//   clusters/<hash>         each of its pages (hashes: in the index blob)
// A save writes the blobs the file lacks and keeps those a live page store
// still reads (undo history); a load reads and checks each index, checks
// that every page is there, and reads no page: they load on demand.
#include <map>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "scene/scene_state.h"
#include "scene/sqlite_db.h"
#include "scene/terrain_file.h"

namespace hs::scene {

// Every cluster blob the state needs (pages read through their stores only
// when the file lacks them).
void addClusterBlobs(const SceneState& state, std::map<std::string, BlobSource>& out);

// Whether a save to `path` that no longer needs `key` keeps it: a cluster
// blob a live page store still reads from that file. `live` caches the
// stores' hashes for one save (filled on first use).
bool keepClusterBlob(const std::string& path, const std::string& key, std::optional<std::unordered_set<uint64_t>>& live);

// After a save to `path` wrote every page: the state's stores read from it.
void settleClusterPages(const SceneState& state, const std::string& path);

// Reads each asset's cluster index (state from sceneFromJson) and gives it
// a store reading pages from `path`. A damaged or unsound index (errors not
// monotonic, ...) drops the hierarchy with a warning naming the asset (the
// asset keeps its coarse mesh and still renders); missing pages and cluster
// blobs nothing refers to are reported too.
bool loadClusterIndexes(SqliteDb& db, SceneState& state, const std::string& path, std::vector<std::string>& warnings,
                        std::string& error);

}  // namespace hs::scene
