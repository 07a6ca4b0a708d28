#include "scene/foliage_file.h"

#include <set>

#include "core/content_hash.h"
#include "foliage/manifest.h"
#include "scene/blob_parts.h"

namespace hs::scene {
namespace {

// The cell keys a manifest lists (after foliageFromJson checked it).
std::set<std::string> listedCells(const Json& manifest) {
  std::set<std::string> out;
  const Json* cells = JsonReader::member(manifest, "cells");
  if (!cells || !cells->is_array()) return out;
  for (const Json& e : *cells) {
    const Json* k = JsonReader::member(e, "cell");
    if (!k || !k->is_array() || k->size() != 3) continue;
    out.insert(foliage::cellBlobKey({(*k)[0].get<int32_t>(), (*k)[1].get<int32_t>(), (*k)[2].get<int32_t>()}));
  }
  return out;
}

}  // namespace

Json foliageToJson(const SceneState& state) {
  if (!state.foliage) return nullptr;
  if (state.foliage->pendingManifest) return *state.foliage->pendingManifest;
  if (state.foliage->empty()) return nullptr;
  return foliage::manifestJson(state.foliage->store());
}

bool foliageFromJson(const Json& manifest, SceneState& state, std::string& error) {
  // The manifest checked and the types read; the cells wait for their blobs.
  foliage::FoliageStore store;
  foliage::LoadReport ignored;
  if (!foliage::loadStore(manifest, [](const foliage::CellKey&) { return std::nullopt; }, store, ignored, error))
    return false;
  state.foliage = std::make_shared<FoliageData>(std::move(store));
  state.foliage->pendingManifest = manifest;
  return true;
}

void addFoliageBlobs(const SceneState& state, std::map<std::string, BlobSource>& out) {
  if (!state.foliage || state.foliage->pendingManifest) return;  // cells not loaded: the file keeps its own
  for (const auto& [key, cell] : state.foliage->store().cells()) {
    BlobSource b;
    b.hash = toHex(foliage::cellContentHash(cell));
    b.bytes = [k = key, data = state.foliage] { return foliage::encodeCell(k, *data->store().cell(k)); };
    b.foliageCell = true;
    out[foliage::cellBlobKey(key)] = std::move(b);
  }
}

std::set<std::string> foliageCellKeys(const SceneState& state) {
  if (!state.foliage) return {};
  if (state.foliage->pendingManifest) return listedCells(*state.foliage->pendingManifest);
  std::set<std::string> out;
  for (const auto& [k, c] : state.foliage->store().cells()) out.insert(foliage::cellBlobKey(k));
  return out;
}

void loadFoliageCells(SqliteDb& db, SceneState& state, const std::string& path, std::vector<std::string>& warnings) {
  if (!state.foliage || !state.foliage->pendingManifest) return;
  SqliteStmt q(db, kReadBlobPartsSql);
  auto readBlob = [&](const foliage::CellKey& k) -> std::optional<std::vector<uint8_t>> {
    std::string e;
    std::vector<uint8_t> bytes;
    if (readBlobParts(q, foliage::cellBlobKey(k), bytes, e) != BlobRead::Ok) return std::nullopt;
    return bytes;
  };
  foliage::FoliageStore store;
  foliage::LoadReport report;
  std::string error;
  if (!foliage::loadStore(*state.foliage->pendingManifest, readBlob, store, report, error)) {
    // foliageFromJson read this manifest already; only a changed file gets here.
    warnings.push_back(path + ": " + error + "; the scene's foliage was not loaded");
    store = foliage::FoliageStore();
  }
  for (const std::string& m : report.messages) warnings.push_back(path + ": " + m);
  store.markSaved();
  state.foliage = std::make_shared<FoliageData>(std::move(store));
}

}  // namespace hs::scene
