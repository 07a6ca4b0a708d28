#include "foliage/manifest.h"

#include <algorithm>

#include "core/content_hash.h"

namespace hs::foliage {

uint64_t rawPayloadHash(const Cell& cell);  // store.cpp

uint64_t cellContentHash(const Cell& cell) { return rawPayloadHash(cell); }

Json manifestJson(const FoliageStore& store) {
  Json j = Json::object();
  j["version"] = 1;
  j["next_id"] = store.nextId();
  j["types"] = typesToJson(store.types())["types"];
  std::vector<CellKey> keys;
  for (const auto& [k, c] : store.cells()) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  Json cells = Json::array();
  for (const CellKey& k : keys) {
    const Cell& c = *store.cell(k);
    Json e = Json::object();
    e["cell"] = Json::array({k.x, k.y, k.z});
    e["instances"] = c.count();
    e["hash"] = toHex(cellContentHash(c));
    cells.push_back(std::move(e));
  }
  j["cells"] = std::move(cells);
  return j;
}

Json infoJson(const FoliageStore& store) {
  std::vector<size_t> count(store.types().size(), 0);
  size_t runBytes = 0;
  for (const auto& [k, c] : store.cells())
    for (const Run& r : c.runs) {
      count[r.type] += r.items.size();
      runBytes += r.items.capacity() * sizeof(PackedInstance);
    }
  Json types = Json::array();
  size_t total = 0;
  for (size_t i = 0; i < count.size(); ++i) {
    Json t = Json::object();
    t["name"] = store.type(i).name;
    t["mesh"] = store.type(i).mesh;
    t["instances"] = count[i];
    t["bytes"] = count[i] * sizeof(PackedInstance);
    types.push_back(std::move(t));
    total += count[i];
  }
  Json j = Json::object();
  j["types"] = std::move(types);
  j["instances"] = total;
  j["cells"] = store.cellCount();
  j["bytes"] = runBytes + store.cellCount() * (sizeof(Cell) + sizeof(CellKey));
  return j;
}

bool loadStore(const Json& manifest, const std::function<std::optional<std::vector<uint8_t>>(const CellKey&)>& readBlob,
               FoliageStore& out, LoadReport& report, std::string& error) {
  JsonReader r(error);
  if (!r.object(manifest, "foliage")) return false;
  for (auto it = manifest.begin(); it != manifest.end(); ++it)
    if (it.key() != "version" && it.key() != "next_id" && it.key() != "types" && it.key() != "cells")
      return r.fail(jsonPath("foliage", it.key()), "unknown key in the foliage manifest");
  int version = 0;
  const Json* v = r.required(manifest, "foliage", "version");
  if (!v || !r.integer(*v, "foliage.version", version, 1, 1)) return false;
  int64_t nextId = 1;
  const Json* n = r.required(manifest, "foliage", "next_id");
  if (!n || !r.integer(*n, "foliage.next_id", nextId, 1, int64_t(UINT32_MAX))) return false;
  const Json* types = r.required(manifest, "foliage", "types");
  if (!types) return false;
  Json wrapped = Json::object();
  wrapped["types"] = *types;
  std::vector<FoliageType> list;
  std::string typeError;
  if (!typesFromJson(wrapped, list, typeError)) {
    error = "foliage." + typeError;
    return false;
  }
  const Json* cells = r.required(manifest, "foliage", "cells");
  if (!cells || !r.array(*cells, "foliage.cells")) return false;

  FoliageStore store;
  for (const FoliageType& t : list) {
    std::vector<std::string> warnings;
    store.addType(t, warnings);
  }
  for (size_t i = 0; i < cells->size(); ++i) {
    const std::string path = jsonIndex("foliage.cells", i);
    const Json& e = (*cells)[i];
    if (!r.object(e, path)) return false;
    const Json* key = r.required(e, path, "cell");
    double k[3];
    if (!key || !r.numbers(*key, jsonPath(path, "cell"), k, 3, "[x, y, z]")) return false;
    for (double c : k)
      if (c != double(int32_t(c))) return r.fail(jsonPath(path, "cell"), "cell coordinates are whole 32-bit numbers");
    const CellKey ck{int32_t(k[0]), int32_t(k[1]), int32_t(k[2])};
    int64_t count = 0;
    const Json* cnt = r.required(e, path, "instances");
    if (!cnt || !r.integer(*cnt, jsonPath(path, "instances"), count, 0, int64_t(UINT32_MAX))) return false;
    std::string hashText;
    uint64_t hash = 0;
    const Json* h = r.required(e, path, "hash");
    if (!h || !r.string(*h, jsonPath(path, "hash"), hashText)) return false;
    if (!fromHex(hashText, hash)) return r.fail(jsonPath(path, "hash"), "expected 16 hex digits");

    auto drop = [&](const std::string& why) {
      ++report.cellsDropped;
      report.instancesDropped += size_t(count);
      report.messages.push_back(why + "; its " + std::to_string(count) + " instances are not loaded");
    };
    const std::optional<std::vector<uint8_t>> blob = readBlob(ck);
    if (!blob) {
      drop("foliage cell " + cellName(ck) + ": blob \"" + cellBlobKey(ck) + "\" is missing from the file");
      continue;
    }
    Cell cell;
    const Status st = decodeCell(*blob, ck, store.types().size(), cell);
    if (!st) {
      drop(st.error);
      continue;
    }
    if (cellContentHash(cell) != hash) {
      drop("foliage cell " + cellName(ck) + ": the blob is another version of the cell (hash " +
           toHex(cellContentHash(cell)) + ", the scene expects " + hashText + ")");
      continue;
    }
    if (cell.count() != size_t(count)) {
      drop("foliage cell " + cellName(ck) + ": the blob holds " + std::to_string(cell.count()) +
           " instances, the scene expects " + std::to_string(count));
      continue;
    }
    const Status loaded = store.load(ck, *blob);
    if (!loaded) {
      drop(loaded.error);
      continue;
    }
    ++report.cellsLoaded;
  }
  store.setNextId(std::max(store.nextId(), uint32_t(nextId)));
  out = std::move(store);
  return true;
}

}  // namespace hs::foliage
