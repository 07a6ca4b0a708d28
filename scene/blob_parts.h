#pragma once
// Reading one logical blob of the .hscene's blobs table (hscene_file.h):
// its parts in order, joined. Every reader of the table (meshes, textures,
// LUTs, OpenColorIO files, foliage cells, cluster indexes and pages, the
// repair's salvage) reads through this one loop and words the outcome as
// its messages need.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/sqlite_db.h"

namespace hs::scene {

// The statement readBlobParts steps (one per loop of reads, reused).
inline constexpr const char* kReadBlobPartsSql = "SELECT part, data FROM blobs WHERE key = ?1 ORDER BY part";

enum class BlobRead {
  Ok,
  Missing,      // no part at all
  PartMissing,  // a gap in the parts (damaged file)
  Failed,       // SQLite could not read it (`sqlError` says why)
};

// Appends blob `key`'s bytes to `bytes`, reading with `q` (prepared from
// kReadBlobPartsSql), and leaves `q` reset.
BlobRead readBlobParts(SqliteStmt& q, const std::string& key, std::vector<uint8_t>& bytes, std::string& sqlError);

// What a load says of a read that was not Ok, after the owner's name:
// "a part of its data is missing (damaged file)", "the scene file is
// damaged (<SQLite's words>)", "its data is missing from the file"; "" for Ok.
std::string blobReadProblem(BlobRead result, const std::string& sqlError);

}  // namespace hs::scene
