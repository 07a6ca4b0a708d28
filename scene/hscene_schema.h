#pragma once
// What a .hscene file's tables must look like before anything is read from
// them (hscene_file.h has the schema). A file edited with the sqlite3 shell,
// or damaged, may lack a table or hold one with other columns; reading it
// as if it were whole would dereference what is not there.
#include <string>
#include <vector>

#include "scene/scene_state.h"
#include "scene/sqlite_db.h"

namespace hs::scene {

struct SchemaCheck {
  bool hasDocument = false;
  bool hasBlobs = false;
  // A table that exists with a missing or mistyped column: "table blobs:
  // column data is declared TEXT, expected BLOB". Empty when all fit.
  std::string problem;
};

// Reads the tables' declarations (sqlite_master, PRAGMA table_info);
// `error` is set only when SQLite cannot read them (damage).
SchemaCheck checkSchema(SqliteDb& db, std::string& error);

// Blob keys that belong to no asset, terrain or standalone texture of `state` (left by a tool
// that edited the description alone): counted and named, never read. The
// next save removes them.
std::vector<std::string> danglingBlobKeys(SqliteDb& db, const SceneState& state, std::string& error);

}  // namespace hs::scene
