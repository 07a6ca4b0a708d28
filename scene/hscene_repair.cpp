#include "scene/hscene_repair.h"

#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <unistd.h>

#include "core/content_hash.h"
#include "foliage/impostor_images.h"
#include "scene/blob_parts.h"
#include "scene/cluster_asset.h"
#include "scene/cluster_file.h"
#include "scene/color_lut.h"
#include "scene/demo_scene.h"
#include "scene/hscene_file.h"
#include "scene/legacy_hashes.h"
#include "scene/mesh_blob.h"
#include "scene/mesh_materials.h"
#include "scene/ocio_config.h"
#include "scene/texture_blob.h"
#include "scene/scene_json.h"
#include "scene/sqlite_db.h"
#include "scene/terrain_file.h"

namespace hs::scene {

namespace fs = std::filesystem;

namespace {

// The private copy the salvage reads (and SQLite may roll back a journal
// into): removed when done.
struct ScratchCopy {
  fs::path dir;
  fs::path file;
  ~ScratchCopy() {
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
  }
};

// Beside `out`: the repaired file needs that file system's space anyway,
// and a scene of several GB may not fit in /tmp.
bool makeScratchCopy(const std::string& damaged, const std::string& out, ScratchCopy& copy, std::string& error) {
  std::error_code ec;
  std::string pattern = out + ".salvage-XXXXXX";
  if (!::mkdtemp(pattern.data())) {
    error = out + ": cannot make a folder beside it for the copy to salvage from (" + std::strerror(errno) + ")";
    return false;
  }
  copy.dir = pattern;
  copy.file = copy.dir / "damaged.hscene";
  if (!fs::copy_file(damaged, copy.file, ec)) {
    error = damaged + ": cannot be copied to salvage from (" + ec.message() + ")";
    return false;
  }
  // A hot journal goes with it: the copy is then the file SQLite would see.
  if (fs::exists(damaged + "-journal", ec)) fs::copy_file(damaged + "-journal", copy.file.string() + "-journal", ec);
  return true;
}

int formatVersion(SqliteDb& db) {
  SqliteStmt q(db, "SELECT value FROM meta WHERE key = 'format_version'");
  std::string e;
  if (!q.step(e)) return kSceneFormatVersion;  // unreadable: assume this build's
  try {
    return std::stoi(q.text(0));
  } catch (...) {
    return kSceneFormatVersion;
  }
}

// One logical blob's bytes, its parts in order; false with `why`.
bool readBlobBytes(SqliteDb& db, const std::string& key, std::vector<uint8_t>& bytes, std::string& why) {
  SqliteStmt q(db, kReadBlobPartsSql);
  if (!q.ok()) {
    why = "the blobs table cannot be read (" + db.lastError() + ")";
    return false;
  }
  std::string e;
  switch (readBlobParts(q, key, bytes, e)) {
    case BlobRead::Ok: return true;
    case BlobRead::PartMissing: why = "a part of its data is missing"; break;
    case BlobRead::Failed: why = "its data cannot be read (" + e + ")"; break;
    case BlobRead::Missing: why = "its data is missing from the file"; break;
  }
  return false;
}

// One logical mesh blob read part by part; nullopt with `why` when a part
// is missing or unreadable, it does not decode, or it does not match `hash`.
std::optional<mesh::MeshData> readMesh(SqliteDb& db, const std::string& key, uint64_t hash, int version,
                                       std::string& why) {
  std::vector<uint8_t> bytes;
  if (!readBlobBytes(db, key, bytes, why)) return std::nullopt;
  std::string e;
  std::optional<mesh::MeshData> m = decodeMesh(bytes.data(), bytes.size(), key, e);
  if (!m) {
    why = "its data does not decode (" + e + ")";
    return std::nullopt;
  }
  if ((version < 4 ? legacyMeshHash(*m) : mesh::contentHash(*m)) != hash) {
    why = "its data does not match its checksum";
    return std::nullopt;
  }
  return m;
}

// The description, or nullopt with why it cannot be read.
// Values out of their fields' ranges are clamped and named in `clamped`.
std::optional<SceneState> readDescription(SqliteDb& db, std::string& why, std::vector<std::string>& clamped) {
  SqliteStmt q(db, "SELECT json FROM document WHERE id = 1");
  if (!q.ok()) {
    why = db.lastError();
    return std::nullopt;
  }
  std::string e, text;
  if (q.step(e)) text = q.text(0);
  if (!e.empty() || text.empty()) {
    why = e.empty() ? "it is missing" : e;
    return std::nullopt;
  }
  bool notJson = false;
  std::optional<SceneState> s = sceneFromJsonText(text, e, notJson, &clamped);
  if (!s) why = (notJson ? "not valid JSON: " : "invalid: ") + e;
  return s;
}

// Materials and textures (format 5) of the assets kept: a lost asset's
// materials and mesh textures go with it; a standalone texture whose data
// does not verify is dropped and the materials using it lose that map.
void salvageMaterials(SqliteDb& db, SceneState& s, const std::set<AssetId>& lost, RepairReport& r) {
  std::set<TextureId> goneTextures;
  for (auto it = s.textures.begin(); it != s.textures.end();) {
    TextureAsset& t = it->second;
    std::string why;
    if (!t.standalone()) {
      if (lost.count(t.asset)) why = "its mesh asset was lost";
    } else {
      const std::string what = "texture " + std::to_string(t.id) + " ('" + t.name + "')";
      std::vector<uint8_t> bytes;
      std::string e;
      if (!readBlobBytes(db, "texture/" + std::to_string(t.id), bytes, why)) {
      } else if (auto image = decodeTexture(bytes.data(), bytes.size(), what, e); !image) {
        why = e;
      } else if (textureContentHash(*image) != t.contentHash) {
        why = "its data does not match its checksum";
      } else {
        t.image = std::make_shared<const mesh::Texture>(std::move(*image));
      }
    }
    if (!why.empty()) {
      if (t.standalone()) r.dropped.push_back("texture " + std::to_string(t.id) + " ('" + t.name + "'): " + why);
      goneTextures.insert(it->first);
      it = s.textures.erase(it);
      continue;
    }
    ++it;
  }
  for (auto it = s.materials.begin(); it != s.materials.end();) {
    if (lost.count(it->second.asset)) {
      it = s.materials.erase(it);
      continue;
    }
    for (TextureId* t : {&it->second.baseColorTexture, &it->second.normalMap, &it->second.heightMap})
      if (goneTextures.count(*t)) *t = kNoTexture;
    ++it;
  }
  std::string e;
  if (!linkMeshTextures(s, e)) r.notes.push_back("mesh textures: " + e);
}

// Keeps each asset whose mesh verifies (its LODs too, or none of them);
// entities showing a dropped asset keep their place without the mesh.
void salvageMeshes(SqliteDb& db, SceneState& s, int version, RepairReport& r) {
  std::set<AssetId> lost;
  for (auto it = s.assets.begin(); it != s.assets.end();) {
    MeshAsset& a = it->second;
    const std::string what = "mesh asset " + std::to_string(a.id) + " ('" + a.name + "')";
    std::string why;
    auto m = readMesh(db, "mesh/" + std::to_string(a.id), a.contentHash, version, why);
    if (!m) {
      r.dropped.push_back(what + ": " + why);
      lost.insert(a.id);
      it = s.assets.erase(it);
      continue;
    }
    a.data = std::make_shared<const mesh::MeshData>(std::move(*m));
    for (size_t k = 0; k < a.lods.size(); ++k) {
      auto lod = readMesh(db, "mesh/" + std::to_string(a.id) + "/lod" + std::to_string(k + 1), a.lods[k].contentHash,
                          version, why);
      if (!lod) {
        r.dropped.push_back(what + ": its LOD " + std::to_string(k + 1) + " and coarser (" + why +
                            "); the full mesh is kept, LODs can be made again");
        a.lods.resize(k);
        break;
      }
      a.lods[k].data = std::make_shared<const mesh::MeshData>(std::move(*lod));
    }
    if (a.impostorHash != 0) {  // derived data: dropped if it does not verify, baked again later
      std::vector<uint8_t> bytes;
      std::optional<foliage::ImpostorImages> im;
      if (readBlobBytes(db, "mesh/" + std::to_string(a.id) + "/impostor", bytes, why) &&
          (im = foliage::decodeImpostor(bytes, "impostor", why)) && im->contentHash() == a.impostorHash) {
        a.impostor = std::make_shared<const foliage::ImpostorImages>(std::move(*im));
      } else {
        r.dropped.push_back(what + ": its impostor (" + (im ? std::string("its hash does not match") : why) +
                            "); the renderer bakes it again");
        a.impostorHash = 0;
      }
    }
    if (version < 4) {
      a.contentHash = mesh::contentHash(*a.data);
      for (auto& lod : a.lods) lod.contentHash = mesh::contentHash(*lod.data);
    }
    ++it;
  }
  for (auto& [id, e] : s.entities)
    if (e.mesh && lost.count(e.mesh->mesh)) {
      r.dropped.push_back("entity " + std::to_string(id) + " ('" + e.name + "'): its mesh (asset " +
                          std::to_string(e.mesh->mesh) + "); the entity is kept");
      e.mesh.reset();
    }
  salvageMaterials(db, s, lost, r);
}

// Cluster hierarchies: each page read and checked (a load reads none); a
// hierarchy with a damaged or missing page is dropped and noted, its asset
// keeping its coarse mesh (the copy could not hold the page).
void salvageClusters(SceneState& s, RepairReport& r, const std::function<std::string(std::string)>& named) {
  for (auto& [id, a] : s.assets) {
    if (!a.clusters) continue;
    std::string why;
    for (uint32_t p = 0; p < a.clusters->pages->pageCount() && why.empty(); ++p)
      if (!a.clusters->pages->read(p, why)) break;
    if (why.empty()) continue;
    r.dropped.push_back("mesh asset " + std::to_string(id) + " ('" + a.name + "'): its cluster hierarchy (" +
                        named(why) + "); its coarse mesh is kept, importing the scan again rebuilds it");
    a.clusters.reset();
    a.clustersHash = 0;
  }
}

// The grading LUT: kept when its blob verifies, else dropped and noted
// (the scene renders ungraded until a LUT is imported again).
void salvageLut(SqliteDb& db, SceneState& s, RepairReport& r) {
  LutData& lut = s.settings.post.lut;
  if (lut.empty()) return;
  std::vector<uint8_t> bytes;
  std::string why;
  if (readBlobBytes(db, lutBlobKey(lut.contentHash), bytes, why)) {
    auto text = std::make_shared<const std::string>(bytes.begin(), bytes.end());
    if (contentHash(text->data(), text->size()) == lut.contentHash) {
      lut.bytes = std::move(text);
      return;
    }
    why = "its hash does not match";
  }
  r.dropped.push_back("the LUT '" + lut.fileName + "' (" + why + "); `hybridscape-cli lut import` stores one again");
  lut = {};
  s.settings.post.lutEnabled = false;
}

// The OpenColorIO config: kept when every file's blob verifies, else
// dropped and noted (the scene renders with its tone map).
void salvageOcioConfig(SqliteDb& db, SceneState& s, RepairReport& r) {
  OcioConfigData& ocio = s.settings.post.ocioConfig;
  if (ocio.empty()) return;
  std::string why;
  for (OcioFile& f : ocio.files) {
    std::vector<uint8_t> bytes;
    if (!readBlobBytes(db, ocioBlobKey(f.contentHash), bytes, why)) {
      why = "'" + f.path + "': " + why;
      break;
    }
    auto text = std::make_shared<const std::string>(bytes.begin(), bytes.end());
    if (contentHash(text->data(), text->size()) != f.contentHash) {
      why = "'" + f.path + "': its hash does not match";
      break;
    }
    f.bytes = std::move(text);
  }
  if (why.empty()) return;
  r.dropped.push_back("the OpenColorIO config '" + ocio.fileName + "' (" + why +
                      "); `hybridscape-cli ocio import` stores one again");
  ocio = {};
  s.settings.post.viewTransform = false;
}

// Without a description, meshes are found by their blob keys ("mesh/<id>")
// and checked against the hash stored beside them; each becomes an entity
// at the origin of a starter scene, so its data is not lost.
void salvageOrphanMeshes(SqliteDb& db, SceneState& s, RepairReport& r) {
  SqliteStmt q(db, "SELECT key, hash FROM blobs WHERE part = 0");
  if (!q.ok()) {
    r.dropped.push_back("every mesh: the blobs table cannot be read (" + db.lastError() + ")");
    return;
  }
  std::vector<std::pair<AssetId, std::string>> found;
  std::string e;
  while (q.step(e)) {
    const std::string key = q.text(0);
    if (key.rfind("mesh/", 0) != 0 || key.find('/', 5) != std::string::npos) continue;
    try {
      found.emplace_back(AssetId(std::stoull(key.substr(5))), q.text(1));
    } catch (...) {
    }
  }
  if (!e.empty()) r.dropped.push_back("some meshes: the blobs table is damaged (" + e + ")");
  for (const auto& [id, hex] : found) {
    uint64_t hash = 0;
    std::string why;
    std::optional<mesh::MeshData> m =
        fromHex(hex, hash) ? readMesh(db, "mesh/" + std::to_string(id), hash, kSceneFormatVersion, why) : std::nullopt;
    if (!m) {
      r.dropped.push_back("stored mesh " + std::to_string(id) + ": " + (why.empty() ? "its checksum is unreadable" : why));
      continue;
    }
    MeshAsset a;
    a.id = s.maxAssetId() + 1;
    a.name = "Recovered mesh " + std::to_string(id);
    a.contentHash = hash;
    a.data = std::make_shared<const mesh::MeshData>(std::move(*m));
    Entity ent;
    ent.id = s.maxEntityId() + 1;
    ent.name = a.name;
    ent.mesh = MeshInstance{a.id};
    s.roots.push_back(ent.id);
    s.entities.emplace(ent.id, std::move(ent));
    s.assets.emplace(a.id, std::move(a));
  }
}

}  // namespace

bool repairScene(const std::string& damaged, const std::string& out, RepairReport& r, std::string& error) {
  std::error_code ec;
  if (!fs::exists(damaged, ec)) {
    error = damaged + ": file not found";
    return false;
  }
  if (fs::exists(out, ec)) {
    error = out + (fs::equivalent(damaged, out, ec) ? ": is the damaged file itself; the repaired copy goes to a new file"
                                                     : ": already exists; the repaired copy goes to a new file");
    return false;
  }
  ScratchCopy copy;
  if (!makeScratchCopy(damaged, out, copy, error)) return false;

  // A file that opens needs no salvage: the copy is a plain save of it.
  LoadReport load;
  std::string openError;
  std::optional<SceneState> state = loadScene(copy.file.string(), openError, nullptr, &load);
  const std::string shown = copy.file.string();
  auto named = [&](std::string line) {  // messages about the copy name the user's file
    for (size_t at; (at = line.find(shown)) != std::string::npos;) line.replace(at, shown.size(), damaged);
    return line;
  };
  for (const std::string& w : load.warnings) r.notes.push_back(named(w));
  if (state) {
    r.wasWhole = true;
  } else {
    r.notes.push_back("opening it failed: " + named(openError));
    {
      std::ifstream f(copy.file, std::ios::binary);
      char header[16] = {};
      f.read(header, sizeof header);
      if (f.gcount() != 16 || std::memcmp(header, "SQLite format 3\0", 16) != 0) {
        error = damaged + ": not an SQLite database (its header is gone); nothing can be salvaged from it";
        return false;
      }
    }
    SqliteDb db;
    std::string e;
    if (!db.open(copy.file.string(), true, false, e)) {
      error = damaged + ": SQLite cannot open it (" + e + "); nothing can be salvaged";
      return false;
    }
    const int version = formatVersion(db);
    std::string why;
    std::vector<std::string> clamped;
    state = readDescription(db, why, clamped);
    for (const std::string& c : clamped) r.notes.push_back(damaged + ": " + c);
    if (state) {
      salvageMeshes(db, *state, version, r);
      std::vector<std::string> clusterWarnings;
      if (!loadClusterIndexes(db, *state, copy.file.string(), clusterWarnings, e)) {
        r.dropped.push_back("cluster hierarchies: " + named(e));
        for (auto& [id, a] : state->assets) a.clustersHash = 0;
      }
      for (const std::string& w : clusterWarnings) r.notes.push_back(named(w));
      salvageLut(db, *state, r);
      salvageOcioConfig(db, *state, r);
      if (!state->terrains.empty() && !loadTerrainTiles(db, *state, damaged, version, e, nullptr)) {
        r.dropped.push_back(std::to_string(state->terrains.size()) + " terrain(s): " + named(e));
        state->terrains.clear();
        for (auto& [id, ent] : state->entities) ent.terrain.reset();
      }
    } else {
      r.dropped.push_back("the scene description (entities, cameras, lights, the sequence): " + why +
                          "; a sun and a camera stand in for it");
      state = buildStarterScene();
      salvageOrphanMeshes(db, *state, r);
      // Terrain tiles cannot be put together without the description.
      SqliteStmt t(db, "SELECT COUNT(DISTINCT key) FROM blobs WHERE key LIKE 'terrain/%'");
      std::string te;
      if (t.ok() && t.step(te) && t.integer(0) > 0)
        r.dropped.push_back(std::to_string(t.integer(0)) +
                            " terrain tile(s): without the description they cannot be placed");
    }
  }
  salvageClusters(*state, r, named);
  r.entities = state->entities.size();
  r.meshes = state->assets.size();
  r.terrains = state->terrains.size();
  if (!saveScene(*state, out, error)) return false;
  return true;
}

const OperationDecl& repairOperation() {
  static const OperationDecl op{
      .name = "repair",
      .summary = "save a repaired copy of a damaged scene",
      .usage = "<damaged.hscene> <repaired.hscene>",
      .description = "Reads what can still be read from a scene that does not open (the description, each mesh "
                     "whose data matches its checksum, terrains whose tiles do) and saves it to a new file, listing "
                     "what was dropped and why. The damaged file is never written; the new one must not exist.",
      .positionals = {{.name = "damaged.hscene", .help = "the scene that does not open"},
                      {.name = "repaired.hscene", .help = "the new file to write"}}};
  return op;
}

}  // namespace hs::scene
