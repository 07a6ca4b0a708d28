#include "scene/terrain_file.h"

#include <cstdio>
#include <cstring>
#include <set>

#include "core/content_hash.h"
#include "scene/legacy_hashes.h"
#include "scene/terrain_json.h"
#include "terrain/tile_blob.h"
#include "terrain/tile_hash.h"

namespace hs::scene {
namespace {

std::string prefixOf(TerrainId id) { return "terrain/" + std::to_string(id) + "/"; }

std::string kindName(terrain::TileKind kind) {
  switch (kind) {
    case terrain::TileKind::Height: return "height";
    case terrain::TileKind::Holes: return "holes";
    case terrain::TileKind::Paint: return "paint";
  }
  return "?";
}

// Parses "h/3_4", "holes/3_4", "paint/2/3_4" (the part after the prefix).
bool parseKey(const std::string& rest, terrain::TileKind& kind, int& layer, int& tx, int& ty) {
  layer = 0;
  int consumed = 0;
  if (std::sscanf(rest.c_str(), "h/%d_%d%n", &tx, &ty, &consumed) == 2 && size_t(consumed) == rest.size()) {
    kind = terrain::TileKind::Height;
    return true;
  }
  if (std::sscanf(rest.c_str(), "holes/%d_%d%n", &tx, &ty, &consumed) == 2 && size_t(consumed) == rest.size()) {
    kind = terrain::TileKind::Holes;
    return true;
  }
  if (std::sscanf(rest.c_str(), "paint/%d/%d_%d%n", &layer, &tx, &ty, &consumed) == 3 && size_t(consumed) == rest.size()) {
    kind = terrain::TileKind::Paint;
    return true;
  }
  return false;
}

// Content hash of a decoded tile as the saver computed it (a sparse tile a
// uniform blob released back to "unallocated" hashes as its fill, i.e. 0).
uint64_t decodedHash(const TerrainData& data, terrain::TileKind kind, int layer, int tile) {
  return data.tileHash(kind, layer, tile);
}

}  // namespace

std::string terrainTileKey(TerrainId id, terrain::TileKind kind, int layer, int tileX, int tileY) {
  const std::string xy = std::to_string(tileX) + "_" + std::to_string(tileY);
  switch (kind) {
    case terrain::TileKind::Height: return prefixOf(id) + "h/" + xy;
    case terrain::TileKind::Holes: return prefixOf(id) + "holes/" + xy;
    case terrain::TileKind::Paint: return prefixOf(id) + "paint/" + std::to_string(layer) + "/" + xy;
  }
  return {};
}

void addTerrainBlobs(const SceneState& state, std::map<std::string, BlobSource>& out) {
  for (const auto& [id, t] : state.terrains) {
    if (!t.data) continue;
    const std::shared_ptr<TerrainData> data = t.data;
    const terrain::Terrain& tr = data->terrain();
    const auto& grid = tr.height.heights();
    const int tiles = grid.tileCount(), tilesX = grid.tilesX();
    for (int i = 0; i < tiles; ++i) {
      BlobSource b;
      b.terrainTile = true;
      b.hash = toHex(data->tileHash(terrain::TileKind::Height, 0, i));
      b.bytes = [data, i] { return terrain::encodeHeightTile(data->terrain().height, i); };
      out[terrainTileKey(id, terrain::TileKind::Height, 0, i % tilesX, i / tilesX)] = std::move(b);
      if (const uint64_t h = data->tileHash(terrain::TileKind::Holes, 0, i)) {
        BlobSource hb;
        hb.terrainTile = true;
        hb.hash = toHex(h);
        hb.bytes = [data, i] { return terrain::encodeHolesTile(data->terrain().height, i); };
        out[terrainTileKey(id, terrain::TileKind::Holes, 0, i % tilesX, i / tilesX)] = std::move(hb);
      }
      for (int l = 0; l < tr.paint.layerCount(); ++l) {
        const uint64_t h = data->tileHash(terrain::TileKind::Paint, l, i);
        if (!h) continue;
        BlobSource pb;
        pb.terrainTile = true;
        pb.hash = toHex(h);
        pb.bytes = [data, l, i] { return terrain::encodePaintTile(data->terrain().paint, l, i); };
        out[terrainTileKey(id, terrain::TileKind::Paint, l, i % tilesX, i / tilesX)] = std::move(pb);
      }
    }
  }
}

SceneState snapshotForSave(const SceneState& state) {
  SceneState s = state;
  for (auto& [id, t] : s.terrains)
    if (t.data) t.data = t.data->snapshot();
  return s;
}

bool loadTerrainTiles(SqliteDb& db, SceneState& state, const std::string& path, int formatVersion, std::string& error,
                      const Progress* progress) {
  // Files before format 4 hold the hand-written hashes of their time.
  const TileHashCache::HashFunction legacy = formatVersion < kFirstXxh3Format ? &legacyTileHash : nullptr;
  size_t done = 0;
  for (auto& [id, t] : state.terrains) {
    reportProgress(progress, double(done++) / double(state.terrains.size()), "Loading terrain tiles");
    TerrainData& data = *t.data;
    terrain::Terrain& tr = data.terrain();
    const auto& grid = tr.height.heights();
    const int tiles = grid.tileCount(), tilesX = grid.tilesX(), layers = tr.paint.layerCount();
    const std::string what = path + ": terrain '" + t.name + "' (id " + std::to_string(id) + ")";
    auto tileName = [&](terrain::TileKind kind, int layer, int tile) {
      return kindName(kind) + (kind == terrain::TileKind::Paint ? " layer " + std::to_string(layer) : "") + " tile " +
             std::to_string(tile % tilesX) + "_" + std::to_string(tile / tilesX);
    };

    // Every blob under the terrain's prefix, in key order.
    const std::string prefix = prefixOf(id);
    std::string upper = prefix;
    upper.back() = char(upper.back() + 1);  // '/' + 1: the first key past the prefix
    SqliteStmt q(db, "SELECT key, part, hash, data FROM blobs WHERE key >= ?1 AND key < ?2 ORDER BY key, part");
    q.bind(1, prefix);
    q.bind(2, upper);
    std::vector<uint8_t> seenHeights(size_t(tiles), 0), seenHoles(size_t(tiles), 0);
    std::vector<std::vector<uint8_t>> seenPaint(size_t(layers), std::vector<uint8_t>(size_t(tiles), 0));
    std::string e;
    size_t row = 0;
    while (q.step(e)) {
      if ((++row & 255) == 0) {
        if (isCancelled(progress)) {
          error = path + ": opening cancelled";
          return false;
        }
        reportProgress(progress, (double(done - 1) + double(row) / double(tiles * (2 + layers))) /
                                     double(state.terrains.size()),
                       "Loading terrain tiles");
      }
      const std::string key = q.text(0);
      terrain::TileKind kind;
      int layer = 0, tx = 0, ty = 0;
      if (!parseKey(key.substr(prefix.size()), kind, layer, tx, ty) || tx < 0 || ty < 0 || tx >= tilesX ||
          ty >= grid.tilesY() || layer < 0 || layer >= layers) {
        error = what + ": the file holds a tile blob '" + key + "' that does not belong to it (damaged file)";
        return false;
      }
      const int tile = ty * tilesX + tx;
      const std::string name = tileName(kind, layer, tile);
      if (q.integer(1) != 0) {
        error = what + ": " + name + " is split into parts it should not have (damaged file)";
        return false;
      }
      const auto bytes = q.blob(3);
      const terrain::Status st = terrain::decodeTile(tr, bytes);
      if (!st) {
        error = what + ": " + name + " is damaged (" + st.error + ")";
        return false;
      }
      // The blob's header names its own tile: it must be the one its key says.
      const uint64_t h = legacy ? data.tileHash(kind, layer, tile, legacy) : decodedHash(data, kind, layer, tile);
      uint64_t expected = 0;
      if (!fromHex(q.text(2), expected) || h != expected) {
        error = what + ": " + name + " does not match its checksum (damaged file)";
        return false;
      }
      auto& seen = kind == terrain::TileKind::Height  ? seenHeights
                   : kind == terrain::TileKind::Holes ? seenHoles
                                                      : seenPaint[size_t(layer)];
      seen[size_t(tile)] = 1;
    }
    if (!e.empty()) {
      error = what + ": the scene file is damaged (" + e + ")";
      return false;
    }
    for (int i = 0; i < tiles; ++i)
      if (!seenHeights[size_t(i)]) {
        error = what + ": " + tileName(terrain::TileKind::Height, 0, i) + " is missing from the file";
        return false;
      }
    // Sparse tiles the description says exist.
    if (!data.described()) {
      error = what + ": the description has no tile summary";
      return false;
    }
    const TerrainData::DescribedTiles summary = *data.described();
    bool ok = true;
    const std::vector<bool> holes = tileBitmapFromText(summary.holes, size_t(tiles), ok);
    const std::vector<std::string>& paint = summary.paint;
    if (!ok || int(paint.size()) != layers) {
      error = what + ": the description's tile summary is damaged";
      return false;
    }
    for (int i = 0; i < tiles; ++i)
      if (holes[size_t(i)] != bool(seenHoles[size_t(i)])) {
        error = what + ": " + tileName(terrain::TileKind::Holes, 0, i) +
                (holes[size_t(i)] ? " is missing from the file" : " is in the file but not in its description (damaged file)");
        return false;
      }
    for (int l = 0; l < layers; ++l) {
      const std::vector<bool> p = tileBitmapFromText(paint[size_t(l)], size_t(tiles), ok);
      if (!ok) {
        error = what + ": the description's tile summary is damaged";
        return false;
      }
      for (int i = 0; i < tiles; ++i)
        if (p[size_t(i)] != bool(seenPaint[size_t(l)][size_t(i)])) {
          error = what + ": " + tileName(terrain::TileKind::Paint, l, i) +
                  (p[size_t(i)] ? " is missing from the file" : " is in the file but not in its description (damaged file)");
          return false;
        }
    }
    // Last, everything together: tiles from another save of the same
    // terrain would pass every check above but this one.
    data.setDescribed(std::nullopt);  // the tiles speak for themselves now
    if (summary.contentHash != data.contentHash(legacy)) {
      error = what + ": its tiles do not add up to the content the description records (damaged file)";
      return false;
    }
    tr.height.updateAllBounds();
  }
  reportProgress(progress, 1.0, "Loaded terrain tiles");
  return true;
}

}  // namespace hs::scene
