#include "scene/hscene_file.h"

#include <charconv>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <unordered_set>

#include <sqlite3.h>
#include <unistd.h>

#include "core/content_hash.h"
#include "core/scratch_files.h"
#include "foliage/impostor_images.h"
#include "scene/blob_parts.h"
#include "scene/cluster_file.h"
#include "scene/color_lut.h"
#include "scene/foliage_file.h"
#include "scene/hscene_recovery.h"
#include "scene/hscene_schema.h"
#include "scene/legacy_hashes.h"
#include "scene/mesh_blob.h"
#include "scene/mesh_materials.h"
#include "scene/ocio_config.h"
#include "scene/scene_json.h"
#include "scene/sqlite_db.h"
#include "scene/terrain_file.h"
#include "scene/texture_blob.h"

namespace hs::scene {
namespace {

constexpr const char* kFormatName = "hybridscape-scene";

const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS document(id INTEGER PRIMARY KEY CHECK (id = 1), json TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS blobs(key TEXT NOT NULL, part INTEGER NOT NULL, hash TEXT NOT NULL,
                                 data BLOB NOT NULL, PRIMARY KEY(key, part));
)sql";

std::string meshKey(AssetId id) { return "mesh/" + std::to_string(id); }
// LOD levels 1, 2, ... of an asset; level 0 is meshKey (files before LODs had only that).
std::string lodKey(AssetId id, size_t level) { return meshKey(id) + "/lod" + std::to_string(level); }
// An asset's baked impostor (format 12, foliage/impostor_images.h).
std::string impostorKey(AssetId id) { return meshKey(id) + "/impostor"; }

// Standalone textures (a mesh's own stay in its blob, material.h).
std::string textureKey(TextureId id) { return "texture/" + std::to_string(id); }

// First 16 bytes of every SQLite 3 database.
bool hasSqliteHeader(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char header[16] = {};
  f.read(header, sizeof header);
  return f.gcount() == 16 && std::memcmp(header, "SQLite format 3\0", 16) == 0;
}

// The size the database's header says it has (page size x page count),
// or 0 when the header does not say (the count is only valid when its
// "version-valid-for" matches the change counter). A file shorter than
// that was cut: SQLite reads the missing tail as zeros, which a blob whose
// last page ends in unused zero bytes would not notice.
uint64_t sqliteDeclaredSize(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char h[100] = {};
  f.read(reinterpret_cast<char*>(h), sizeof h);
  if (f.gcount() != 100) return 0;
  auto be32 = [&](int o) { return uint32_t(h[o]) << 24 | uint32_t(h[o + 1]) << 16 | uint32_t(h[o + 2]) << 8 | h[o + 3]; };
  const uint32_t pageSize = h[16] == 0 && h[17] == 1 ? 65536u : (uint32_t(h[16]) << 8 | h[17]);
  if (be32(92) != be32(24)) return 0;
  return uint64_t(pageSize) * be32(28);
}

// meta.format_version as a number: INT_MAX for a whole number too large for
// an int (a file from far in the future), -1 for text that is no number.
int parseVersion(const std::string& text) {
  int v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ptr != text.data() + text.size() || text.empty()) return -1;
  if (r.ec == std::errc::result_out_of_range) return text[0] == '-' ? -1 : INT_MAX;
  return r.ec == std::errc() ? v : -1;
}

// Reads meta.format / meta.format_version (its text in `versionText`); 0 if
// absent or not a scene.
int readVersion(SqliteDb& db, std::string& format, std::string& error, std::string* versionText = nullptr) {
  // Another program's database has no meta table: that is not damage, it is
  // not a scene (format stays empty). A damaged file fails this read already.
  {
    SqliteStmt t(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'meta'");
    if (!t.ok()) {
      error = db.lastError();
      return 0;
    }
    if (!t.step(error)) return 0;
  }
  SqliteStmt q(db, "SELECT key, value FROM meta WHERE key IN ('format', 'format_version')");
  if (!q.ok()) {
    error = db.lastError();
    return 0;
  }
  int version = 0;
  while (q.step(error)) {
    if (q.text(0) == "format") format = q.text(1);
    if (q.text(0) == "format_version") {
      version = parseVersion(q.text(1));
      if (versionText) *versionText = q.text(1);
    }
  }
  return version;
}

// The logical blobs the state needs: key -> (hash, how to encode it).
// Meshes, and terrain tiles (terrain_file.h).
std::map<std::string, BlobSource> wantedBlobs(const SceneState& s) {
  std::map<std::string, BlobSource> out;
  for (const auto& [id, a] : s.assets) {
    if (a.data) out[meshKey(id)] = {toHex(a.contentHash), [data = a.data] { return encodeMesh(*data); }, false};
    for (size_t k = 0; k < a.lods.size(); ++k)
      if (const auto& data = a.lods[k].data)
        out[lodKey(id, k + 1)] = {toHex(a.lods[k].contentHash), [data] { return encodeMesh(*data); }, false};
    if (a.impostor)
      out[impostorKey(id)] = {toHex(a.impostorHash), [im = a.impostor] { return foliage::encodeImpostor(*im); }, false};
  }
  for (const auto& [id, t] : s.textures)
    if (t.standalone() && t.image)
      out[textureKey(id)] = {toHex(t.contentHash), [image = t.image] { return encodeTexture(*image); }, false};
  if (const LutData& lut = s.settings.post.lut; !lut.empty() && lut.bytes)
    out[lutBlobKey(lut.contentHash)] = {toHex(lut.contentHash), [bytes = lut.bytes] {
                                          return std::vector<uint8_t>(bytes->begin(), bytes->end());
                                        }, false};
  if (const OcioConfigData& ocio = s.settings.post.ocioConfig; !ocio.empty())
    for (const OcioFile& f : ocio.files)
      if (f.bytes)
        out[ocioBlobKey(f.contentHash)] = {toHex(f.contentHash), [bytes = f.bytes] {
                                             return std::vector<uint8_t>(bytes->begin(), bytes->end());
                                           }, false};
  addTerrainBlobs(s, out);
  addFoliageBlobs(s, out);
  addClusterBlobs(s, out);
  return out;
}

bool writeContent(SqliteDb& db, const SceneState& state, const std::string& path, SaveReport& report,
                  std::string& error) {
  if (!db.exec(kSchema, error)) return false;
  {
    SqliteStmt m(db, "INSERT OR REPLACE INTO meta(key, value) VALUES (?1, ?2)");
    for (const auto& [k, v] : {std::pair<std::string, std::string>{"format", kFormatName},
                               {"format_version", std::to_string(kSceneFormatVersion)},
                               {"writer", "Hybridscape 0.1"}}) {
      m.bind(1, k);
      m.bind(2, v);
      m.step(error);
      if (!error.empty()) return false;
      m.reset();
    }
  }
  {
    SqliteStmt d(db, "INSERT OR REPLACE INTO document(id, json) VALUES (1, ?1)");
    const std::string json = writeJson(sceneToJson(state)) + "\n";
    d.bind(1, json);
    d.step(error);
    if (!error.empty()) return false;
  }

  // Which blobs are already there with the right content?
  std::map<std::string, std::string> existing;
  {
    SqliteStmt q(db, "SELECT key, hash FROM blobs WHERE part = 0");
    while (q.step(error)) existing[q.text(0)] = q.text(1);
    if (!error.empty()) return false;
  }
  const auto wanted = wantedBlobs(state);
  SqliteStmt del(db, "DELETE FROM blobs WHERE key = ?1");
  SqliteStmt ins(db, "INSERT INTO blobs(key, part, hash, data) VALUES (?1, ?2, ?3, ?4)");
  for (const auto& [key, source] : wanted) {
    const std::string& hash = source.hash;
    if (auto it = existing.find(key); it != existing.end() && it->second == hash) {
      ++(source.terrainTile   ? report.tilesUnchanged
         : source.foliageCell ? report.cellsUnchanged
         : source.clusterPage ? report.pagesUnchanged
                              : report.blobsUnchanged);
      continue;
    }
    del.bind(1, key);
    del.step(error);
    del.reset();
    if (!error.empty()) return false;
    std::vector<uint8_t> bytes;
    try {
      bytes = source.bytes();  // a cluster page read from the file it came from can fail (cluster_file.h)
    } catch (const std::exception& e) {
      error = e.what();
      return false;
    }
    for (size_t off = 0, part = 0; off < bytes.size() || part == 0; off += kBlobPartBytes, ++part) {
      const size_t n = std::min(kBlobPartBytes, bytes.size() - off);
      ins.bind(1, key);
      ins.bind(2, int64_t(part));
      ins.bind(3, hash);
      ins.bindBlob(4, {bytes.data() + off, n});
      ins.step(error);
      ins.reset();
      if (!error.empty()) return false;
    }
    report.bytesWritten += bytes.size();
    if (source.terrainTile) {
      ++report.tilesWritten;
      report.tileBytesWritten += bytes.size();
    } else if (source.foliageCell) {
      ++report.cellsWritten;
      report.cellBytesWritten += bytes.size();
    } else if (source.clusterPage) {
      ++report.pagesWritten;
    } else {
      ++report.blobsWritten;
    }
  }
  std::optional<std::unordered_set<uint64_t>> livePages;
  for (const auto& [key, hash] : existing) {
    if (wanted.count(key)) continue;
    if (keepClusterBlob(path, key, livePages)) {
      ++report.pagesKept;
      continue;
    }
    del.bind(1, key);
    del.step(error);
    del.reset();
    if (!error.empty()) return false;
    const bool page = key.rfind("clusters/", 0) == 0 && key.rfind("clusters/index/", 0) != 0;
    ++(key.rfind("terrain/", 0) == 0   ? report.tilesRemoved
       : key.rfind("foliage/", 0) == 0 ? report.cellsRemoved
       : page                          ? report.pagesRemoved
                                       : report.blobsRemoved);
  }
  return true;
}

}  // namespace

int sceneFileVersion(const std::string& path) {
  if (!hasSqliteHeader(path)) return 0;
  SqliteDb db;
  std::string error, format;
  if (!db.open(path, true, false, error)) return 0;
  const int v = readVersion(db, format, error);
  return format == kFormatName ? v : 0;
}

bool saveScene(const SceneState& state, const std::string& path, std::string& error,
               SaveReport* reportOut) {
  const auto start = std::chrono::steady_clock::now();
  SaveReport report;
  std::error_code ec;
  namespace fs = std::filesystem;
  if (fs::is_directory(path, ec)) {
    error = path + ": is a directory; choose a file name ending in .hscene";
    return false;
  }

  // A hot journal left by an interrupted save belongs to the file as it is:
  // play it back first. Left there, it would be played back later into
  // whatever this save writes, or make the version read below fail and this
  // save replace the scene wholesale.
  {
    std::string message;
    if (recoverInterruptedSave(path, message) == JournalRecovery::Failed) {
      error = message;
      return false;
    }
  }

  // An existing scene of our format and version: update it in place, in one
  // transaction (SQLite's journal makes it all-or-nothing across a crash).
  const int existingVersion = fs::exists(path, ec) ? sceneFileVersion(path) : 0;
  if (existingVersion == kSceneFormatVersion) {
    SqliteDb db;
    std::string e;
    if (!db.open(path, false, false, e)) {
      error = path + ": cannot open for writing: " + e;
      return false;
    }
    report.incremental = true;
    if (!db.exec("BEGIN IMMEDIATE", e) || !writeContent(db, state, path, report, e) || !db.exec("COMMIT", e)) {
      std::string ignored;
      db.exec("ROLLBACK", ignored);
      // A large save spills pages into the file before COMMIT; after an I/O
      // error (a full disk) SQLite leaves their originals in a hot journal
      // that the next connection plays back. Open one now, so the file is
      // back to what it was before this function returns.
      db.close();
      SqliteDb recover;
      if (recover.open(path, false, false, ignored)) recover.exec("SELECT count(*) FROM sqlite_master", ignored);
      error = path + ": save failed, the file is unchanged: " + e;
      return false;
    }
  } else {
    // New file (or replacing something that is not a current scene): write a
    // complete database beside it, then rename over the target atomically.
    // Its name carries this machine and process, so that what a save killed
    // part-way left (as large as the scene) goes at the next new save here.
    const fs::path target(path);
    const std::string prefix = target.filename().string() + ".saving-";
    sweepStaleScratch(target.has_parent_path() ? target.parent_path() : fs::path("."), prefix);
    const std::string tmp = (target.parent_path() / scratchName(prefix)).string();
    {
      SqliteDb db;
      std::string e;
      if (!db.open(tmp, false, true, e)) {
        error = path + ": cannot create the file: " + e;
        return false;
      }
      if (!db.exec("PRAGMA journal_mode=DELETE; BEGIN", e) || !writeContent(db, state, path, report, e) ||
          !db.exec("COMMIT", e)) {
        db.close();
        fs::remove(tmp, ec);
        fs::remove(tmp + "-journal", ec);  // left by a failed spill of a large save
        error = path + ": save failed, nothing was written: " + e;
        return false;
      }
    }
    fs::rename(tmp, path, ec);
    if (ec) {
      fs::remove(tmp, ec);
      error = path + ": cannot replace the file: " + ec.message();
      return false;
    }
  }
  // Every page is in the file now: stores read from there, memory lets go.
  settleClusterPages(state, path);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (reportOut) *reportOut = report;
  return true;
}

std::optional<SceneState> loadScene(const std::string& path, std::string& error,
                                    const Progress* progress, LoadReport* report) {
  LoadReport ignoredReport;
  if (!report) report = &ignoredReport;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    error = path + ": file not found";
    return std::nullopt;
  }
  if (fs::is_directory(path, ec)) {
    error = path + ": is a directory, not a scene file";
    return std::nullopt;
  }
  if (fs::file_size(path, ec) == 0) {
    error = path + ": file is empty (0 bytes), not a scene";
    return std::nullopt;
  }
  if (!hasSqliteHeader(path)) {
    error = path + ": not a Hybridscape scene (it is not an SQLite database)";
    return std::nullopt;
  }
  {
    std::string message;
    switch (recoverInterruptedSave(path, message)) {
      case JournalRecovery::None: break;
      case JournalRecovery::RolledBack:
      case JournalRecovery::StrayRemoved: report->warnings.push_back(message); break;
      case JournalRecovery::Failed: error = message; return std::nullopt;
    }
  }
  // After any journal is played back (which restores the file's size): a
  // file shorter than its header declares was cut short.
  if (const uint64_t declared = sqliteDeclaredSize(path), actual = fs::file_size(path, ec);
      declared > 0 && actual < declared) {
    error = path + ": the scene file is cut short (" + std::to_string(actual) + " of " + std::to_string(declared) +
            " bytes) and was not opened (damaged file)";
    return std::nullopt;
  }
  SqliteDb db;
  std::string e, format, versionText;
  if (!db.open(path, true, false, e)) {
    error = path + ": cannot open: " + e;
    return std::nullopt;
  }
  const int version = readVersion(db, format, e, &versionText);
  if (!e.empty()) {
    error = path + ": the scene file is damaged and was not opened (" + e + ")";
    return std::nullopt;
  }
  if (format != kFormatName) {
    error = path + ": an SQLite database, but not a Hybridscape scene (no scene format marker)";
    return std::nullopt;
  }
  if (version > kSceneFormatVersion) {
    error = path + ": written by a newer Hybridscape (scene format " + versionText +
            "; this build reads up to " + std::to_string(kSceneFormatVersion) +
            "). Update Hybridscape to open it.";
    return std::nullopt;
  }
  if (version < 1) {
    error = path + (versionText.empty() ? std::string(": no scene format version")
                                        : ": invalid scene format version '" + versionText + "'") +
            " (expected a whole number from 1)";
    return std::nullopt;
  }

  // The tables, before any is read: a missing or reshaped one is named,
  // never queried as if it were there.
  const SchemaCheck schema = checkSchema(db, e);
  if (!e.empty()) {
    error = path + ": the scene file is damaged and was not opened (" + e + ")";
    return std::nullopt;
  }
  if (!schema.hasDocument) {
    error = path + ": the scene file is damaged and was not opened (its table 'document', the scene description, "
                   "is missing)";
    return std::nullopt;
  }
  if (!schema.problem.empty()) {
    error = path + ": the scene file is damaged and was not opened (" + schema.problem + ")";
    return std::nullopt;
  }

  std::string jsonText;
  {
    SqliteStmt q(db, "SELECT json FROM document WHERE id = 1");
    if (q.step(e)) jsonText = q.text(0);
    if (!e.empty() || jsonText.empty()) {
      error = path + ": the scene file is damaged and was not opened (" +
              (e.empty() ? std::string("no scene description") : e) + ")";
      return std::nullopt;
    }
  }
  // A text that is not JSON is damage; JSON that is not a valid description
  // names the bad value's path and its place in the text.
  bool notJson = false;
  std::vector<std::string> clamped;
  std::optional<SceneState> state = sceneFromJsonText(jsonText, e, notJson, &clamped);
  for (const std::string& w : clamped) report->warnings.push_back(path + ": " + w);
  if (!state) {
    error = path + (notJson ? ": the scene description is damaged (not valid JSON): "
                            : ": the scene description is invalid: ") + e;
    return std::nullopt;
  }

  // Without the blobs table there is no bulk data: harmless for a scene
  // that needs none (the next save creates the table), a loss to report by
  // name for one that does.
  if (!schema.hasBlobs) {
    if (!state->assets.empty() || !state->terrains.empty()) {
      error = path + ": the scene file is damaged and was not opened: its table 'blobs' is missing, which held the "
                     "data of " + std::to_string(state->assets.size()) + " mesh asset(s) and " +
              std::to_string(state->terrains.size()) + " terrain(s); its description (" +
              std::to_string(state->entities.size()) + " entities) is readable, but a scene is not opened without "
              "its data";
      return std::nullopt;
    }
    report->warnings.push_back(path + ": its table 'blobs' is missing; the scene needs none (no meshes, no "
                                      "terrains), so nothing is lost, and the next save adds it");
  } else {
    const std::vector<std::string> dangling = danglingBlobKeys(db, *state, e);
    if (!e.empty()) {
      error = path + ": the scene file is damaged and was not opened (" + e + ")";
      return std::nullopt;
    }
    if (!dangling.empty())
      report->warnings.push_back(path + ": " + std::to_string(dangling.size()) +
                                 " stored data block(s) belong to no asset or terrain (first: '" + dangling.front() +
                                 "'); they were ignored and the next save removes them");
  }

  // Bulk data: each asset's mesh and its LOD levels, each checked against
  // the hash the description holds.
  SqliteStmt q(db, kReadBlobPartsSql);
  // One logical blob's bytes, its parts in order; `what` names its owner.
  auto readBlob = [&](const std::string& key, const std::string& what, std::vector<uint8_t>& bytes) {
    const BlobRead r = readBlobParts(q, key, bytes, e);
    if (r != BlobRead::Ok) error = what + ": " + blobReadProblem(r, e);
    return r == BlobRead::Ok;
  };
  // One mesh (or LOD level) decoded and checked.
  auto loadMesh = [&](const std::string& key, const std::string& what, uint64_t hash,
                      std::shared_ptr<const mesh::MeshData>& out, size_t baseTextures = 0) {
    std::vector<uint8_t> bytes;
    if (!readBlob(key, what, bytes)) return false;
    std::optional<mesh::MeshData> mesh = decodeMesh(bytes.data(), bytes.size(), what, e, baseTextures);
    if (!mesh) {
      error = e;
      return false;
    }
    // Files before format 4 hold the hand-written hash of their time.
    if ((version < kFirstXxh3Format ? legacyMeshHash(*mesh) : mesh::contentHash(*mesh)) != hash) {
      error = what + ": its data does not match its checksum (damaged file)";
      return false;
    }
    out = std::make_shared<const mesh::MeshData>(std::move(*mesh));
    return true;
  };
  size_t done = 0;
  for (auto& [id, asset] : state->assets) {
    reportProgress(progress, double(done++) / double(state->assets.size()), "Loading meshes");
    if (isCancelled(progress)) {
      error = path + ": opening cancelled";
      return std::nullopt;
    }
    const std::string what = path + ": mesh asset " + std::to_string(id) + " ('" + asset.name + "')";
    if (!loadMesh(meshKey(id), what, asset.contentHash, asset.data)) return std::nullopt;
    for (size_t k = 0; k < asset.lods.size(); ++k)
      if (!loadMesh(lodKey(id, k + 1), what + ", LOD " + std::to_string(k + 1), asset.lods[k].contentHash,
                    asset.lods[k].data, asset.data->textures.size()))
        return std::nullopt;
    // The impostor is derived data the renderer can bake again: a damaged
    // or missing one is dropped with a warning, the scene still opens.
    if (asset.impostorHash != 0) {
      std::vector<uint8_t> bytes;
      std::optional<foliage::ImpostorImages> im;
      const std::string iw = what + ", impostor";
      std::string ie;
      if (!readBlob(impostorKey(id), iw, bytes)) {
        ie = error;
        error.clear();
      } else if (!(im = foliage::decodeImpostor(bytes, iw, ie))) {
      } else if (im->contentHash() != asset.impostorHash) {
        ie = iw + ": its images do not match the description's hash";
      }
      if (ie.empty()) {
        asset.impostor = std::make_shared<const foliage::ImpostorImages>(std::move(*im));
      } else {
        report->warnings.push_back(ie + "; it was dropped (the renderer bakes it again, "
                                        "`hybridscape-cli foliage impostors` stores it)");
        asset.impostorHash = 0;
      }
    }
    if (version < kFirstXxh3Format) {  // checked by the old hash; the document holds the current one
      asset.contentHash = mesh::contentHash(*asset.data);
      for (auto& lod : asset.lods) lod.contentHash = mesh::contentHash(*lod.data);
    }
  }
  // Materials (format 5): mesh textures point into their meshes, standalone
  // ones come from their blobs. Older files get them from their meshes.
  if (version < kFirstMaterialsFormat) {
    for (const auto& [id, asset] : std::map<AssetId, MeshAsset>(state->assets)) addMeshMaterials(*state, id);
  } else {
    if (!linkMeshTextures(*state, e)) {
      error = path + ": " + e;
      return std::nullopt;
    }
    for (auto& [id, t] : state->textures) {
      if (!t.standalone()) continue;
      const std::string what = path + ": texture " + std::to_string(id) + " ('" + t.name + "')";
      std::vector<uint8_t> bytes;
      if (!readBlob(textureKey(id), what, bytes)) return std::nullopt;
      std::optional<mesh::Texture> image = decodeTexture(bytes.data(), bytes.size(), what, e);
      if (!image) {
        error = e;
        return std::nullopt;
      }
      if (textureContentHash(*image) != t.contentHash) {
        error = what + ": its data does not match its checksum (damaged file)";
        return std::nullopt;
      }
      t.image = std::make_shared<const mesh::Texture>(std::move(*image));
    }
  }
  // The grading LUT (format 13): a missing or damaged one is dropped with a
  // warning and the scene renders ungraded; the rest opens.
  if (LutData& lut = state->settings.post.lut; !lut.empty()) {
    const std::string what = path + ": LUT '" + lut.fileName + "'";
    std::vector<uint8_t> bytes;
    std::string problem;
    if (!readBlob(lutBlobKey(lut.contentHash), what, bytes)) {
      problem = error;
      error.clear();
    } else {
      LutData loaded{lut.fileName, std::make_shared<const std::string>(bytes.begin(), bytes.end()), lut.contentHash};
      if (contentHash(loaded.bytes->data(), loaded.bytes->size()) != lut.contentHash)
        problem = what + ": its data does not match its checksum (damaged file)";
      else if ((problem = lutProblem(what, loaded)).empty())
        lut = std::move(loaded);
    }
    if (!problem.empty()) {
      report->warnings.push_back(problem + "; the scene renders without it (`hybridscape-cli lut import` "
                                           "stores a LUT again)");
      lut = {};
      state->settings.post.lutEnabled = false;
    }
  }
  // The OpenColorIO config (format 15): as the LUT, a missing or damaged
  // file drops the config with a warning and the scene renders with its
  // tone map; a display or view the config lacks falls back to its default.
  if (OcioConfigData& ocio = state->settings.post.ocioConfig; !ocio.empty()) {
    const std::string what = path + ": OpenColorIO config '" + ocio.fileName + "'";
    std::string problem;
    for (OcioFile& f : ocio.files) {
      std::vector<uint8_t> bytes;
      if (!readBlob(ocioBlobKey(f.contentHash), what + ", file '" + f.path + "'", bytes)) {
        problem = error;
        error.clear();
        break;
      }
      auto loaded = std::make_shared<const std::string>(bytes.begin(), bytes.end());
      if (contentHash(loaded->data(), loaded->size()) != f.contentHash) {
        problem = what + ", file '" + f.path + "': its data does not match its checksum (damaged file)";
        break;
      }
      f.bytes = std::move(loaded);
    }
    if (problem.empty()) problem = ocioConfigProblem(what, ocio);
    if (!problem.empty()) {
      report->warnings.push_back(problem + "; the scene renders with its tone map (`hybridscape-cli ocio import` "
                                           "stores a config again)");
      ocio = {};
      state->settings.post.viewTransform = false;
    } else if (std::string unknown;
               resolveDisplayView(ocio, state->settings.post.display, state->settings.post.view, unknown),
               !unknown.empty()) {
      report->warnings.push_back(what + ": " + unknown + "; its default display and view are used");
      state->settings.post.display.clear();
      state->settings.post.view.clear();
    }
  }
  // Cluster hierarchies (format 16): their indexes now, their pages on demand.
  if (schema.hasBlobs && !loadClusterIndexes(db, *state, path, report->warnings, error)) return std::nullopt;
  // Terrains' tiles, checked against their hashes and the description.
  if (!state->terrains.empty() &&
      !loadTerrainTiles(db, *state, path, version, error, progress))
    return std::nullopt;
  // Foliage cells: a damaged one is dropped with a warning, the rest load.
  loadFoliageCells(db, *state, path, report->warnings);
  reportProgress(progress, 1.0, "Loaded");
  return state;
}

}  // namespace hs::scene
