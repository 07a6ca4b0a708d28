#pragma once
// Foliage in the .hscene file (docs/foliage.md, "Storage"): the manifest
// (foliage/manifest.h: types, next id, per cell its count and content hash)
// is the description's "foliage" member, and each cell is a logical blob
// of hscene_file.cpp's blob table under foliage::cellBlobKey(), its content
// hash in the table's hash column. A save writes only the cells whose hash
// differs from the file's (after one brush stroke: the few cells it
// touched) and removes the cells that are gone. A load reads each cell
// forgivingly: a missing or damaged cell is dropped with a warning naming
// the file, the cell and the instances lost; every other cell loads.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/json.h"
#include "scene/scene_state.h"
#include "scene/sqlite_db.h"
#include "scene/terrain_file.h"

namespace hs::scene {

// The description's "foliage" member; null when the scene has none.
Json foliageToJson(const SceneState& state);
// Reads the description's "foliage" member (strict: a bad manifest is an
// error naming its JSON path); the types come in now, the cells when the
// file loader reads their blobs (loadFoliageCells).
bool foliageFromJson(const Json& manifest, SceneState& state, std::string& error);

// Adds a blob per foliage cell.
void addFoliageBlobs(const SceneState& state, std::map<std::string, BlobSource>& out);

// The blob keys of the cells the scene's foliage has (or, before its
// cells are loaded, that its description lists).
std::set<std::string> foliageCellKeys(const SceneState& state);

// Fills the cells from the blob table; damaged or missing cells become
// warnings (naming `path`), never an error.
void loadFoliageCells(SqliteDb& db, SceneState& state, const std::string& path, std::vector<std::string>& warnings);

}  // namespace hs::scene
