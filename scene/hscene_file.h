#pragma once
// The .hscene file: one SQLite database (DESIGN.md).
//
//   meta(key TEXT PRIMARY KEY, value TEXT)        format, format_version, writer
//   document(id INTEGER PRIMARY KEY, json TEXT)   the description (scene_json.h), one row
//   blobs(key TEXT, part INTEGER, hash TEXT, data BLOB, PRIMARY KEY(key, part))
//
// Bulk data is a logical blob per key ("mesh/3"), split into parts of at most
// kBlobPartBytes so no single SQLite value nears its 1 GB limit. A save is one
// transaction that rewrites the description and only the blobs whose hash
// changed; a new file is written beside the target and renamed over it.
#include <optional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "scene/scene_state.h"

namespace hs::scene {

constexpr size_t kBlobPartBytes = size_t(256) << 20;

struct SaveReport {
  // Asset blobs (meshes).
  size_t blobsWritten = 0;
  size_t blobsUnchanged = 0;
  size_t blobsRemoved = 0;
  // Terrain tile blobs (terrain_file.h), counted apart: an 8k terrain has
  // thousands, and what matters is how few a save after an edit writes.
  size_t tilesWritten = 0;
  size_t tilesUnchanged = 0;
  size_t tilesRemoved = 0;
  uint64_t tileBytesWritten = 0;
  // Foliage cell blobs (foliage_file.h), counted apart as tiles are.
  size_t cellsWritten = 0;
  size_t cellsUnchanged = 0;
  size_t cellsRemoved = 0;
  uint64_t cellBytesWritten = 0;
  // Cluster pages (cluster_file.h), counted apart; kept: no longer in the
  // scene but still read by an asset undo can bring back.
  size_t pagesWritten = 0;
  size_t pagesUnchanged = 0;
  size_t pagesRemoved = 0;
  size_t pagesKept = 0;
  uint64_t bytesWritten = 0;  // everything, tiles, cells and pages included
  bool incremental = false;  // updated an existing scene file in place
  double seconds = 0.0;
};

// Writes `state` to `path`. On failure returns false with `error` naming the
// file, and whatever was at `path` before is unchanged. Reads terrain tiles
// while it runs: on a worker thread, pass snapshotForSave(state)
// (terrain_file.h) so the user can keep editing the live terrains.
bool saveScene(const SceneState& state, const std::string& path, std::string& error,
               SaveReport* report = nullptr);

// What opening a scene found and did besides reading it, one line each
// naming the file: an interrupted save rolled back, values out of their
// fields' ranges clamped, data that belongs to nothing ignored.
struct LoadReport {
  std::vector<std::string> warnings;
};

// Reads a scene. On failure returns nullopt with `error` saying what is wrong
// with which file (not a scene, damaged, from a newer version, ...). A hot
// journal beside the file (a save that was interrupted) is played back
// first (hscene_recovery.h), which writes to the file.
std::optional<SceneState> loadScene(const std::string& path, std::string& error,
                                    const Progress* progress = nullptr, LoadReport* report = nullptr);

// The format version of a file, without loading it (0 if it is not a scene).
int sceneFileVersion(const std::string& path);

}  // namespace hs::scene
