#pragma once
// A store as a file keeps it: a JSON manifest (the types, the next id, and
// per cell its key, instance count and content hash) beside one blob per
// cell (store.h). The scene's .hscene puts the manifest in its document
// JSON and the blobs in its blob table under cellBlobKey(); this is the
// part of that which needs no SQLite.
//
// Loading is forgiving per cell and strict per value: a bad manifest is an
// error (with the JSON path); a cell whose blob is missing, corrupt,
// truncated or not the version the manifest names (its hash differs) is
// dropped with a message naming the cell and what is wrong (the byte
// offset for damaged blobs), and every other cell loads: one damaged blob
// never loses the rest of the scene's foliage.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "foliage/store.h"

namespace hs::foliage {

// XXH3 of a cell's raw (uncompressed) payload: what its blob's header holds.
uint64_t cellContentHash(const Cell& cell);

// {"version": 1, "next_id": N, "types": [...], "cells": [{"cell": [x, y, z],
//  "instances": n, "hash": "16 hex digits"}, ...]} (cells in key order).
Json manifestJson(const FoliageStore& store);

// What `info` shows: per type its name, mesh, instance count and the bytes
// its records take in memory, then the totals and the cell count.
// {"types": [{"name", "mesh", "instances", "bytes"}], "instances", "cells", "bytes"}
Json infoJson(const FoliageStore& store);

struct LoadReport {
  size_t cellsLoaded = 0, cellsDropped = 0, instancesDropped = 0;
  std::vector<std::string> messages;  // one per dropped cell
};

// `readBlob(key)` returns the blob stored under cellBlobKey(key), or
// nullopt when there is none. False (and `error`) only for a manifest that
// cannot be read; damaged cells go to `report`.
bool loadStore(const Json& manifest, const std::function<std::optional<std::vector<uint8_t>>(const CellKey&)>& readBlob,
               FoliageStore& out, LoadReport& report, std::string& error);

}  // namespace hs::foliage
