#include "scene/hscene_schema.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <map>
#include <set>
#include <utility>

#include "scene/color_lut.h"
#include "scene/foliage_file.h"
#include "scene/ocio_config.h"

namespace hs::scene {
namespace {

struct Column {
  const char* name;
  const char* type;
};

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

// "" when `table` has every column with its declared type.
std::string checkColumns(SqliteDb& db, const std::string& table, std::initializer_list<Column> want,
                         std::string& error) {
  std::map<std::string, std::string> have;  // column -> declared type
  SqliteStmt q(db, "SELECT name, type FROM pragma_table_info(?1)");
  q.bind(1, table);
  while (q.step(error)) have[q.text(0)] = upper(q.text(1));
  if (!error.empty()) return {};
  for (const Column& c : want) {
    const auto it = have.find(c.name);
    if (it == have.end()) return "table " + table + ": column " + c.name + " is missing";
    if (it->second != c.type)
      return "table " + table + ": column " + c.name + " is declared " +
             (it->second.empty() ? std::string("without a type") : it->second) + ", expected " + c.type;
  }
  return {};
}

// "mesh/<id>..." or "terrain/<id>/...": the id, or nullopt for another shape.
std::optional<uint64_t> idAfter(const std::string& key, std::string_view prefix) {
  if (key.rfind(prefix, 0) != 0) return std::nullopt;
  uint64_t id = 0;
  const char* begin = key.data() + prefix.size();
  const char* end = key.data() + key.size();
  const auto r = std::from_chars(begin, end, id);
  if (r.ec != std::errc() || r.ptr == begin || (r.ptr != end && *r.ptr != '/')) return std::nullopt;
  return id;
}

}  // namespace

SchemaCheck checkSchema(SqliteDb& db, std::string& error) {
  SchemaCheck out;
  {
    SqliteStmt t(db, "SELECT name FROM sqlite_master WHERE type = 'table' AND name IN ('document', 'blobs')");
    while (t.step(error)) {
      const std::string name = t.text(0);
      out.hasDocument |= name == "document";
      out.hasBlobs |= name == "blobs";
    }
    if (!error.empty()) return out;
  }
  if (out.hasDocument) out.problem = checkColumns(db, "document", {{"id", "INTEGER"}, {"json", "TEXT"}}, error);
  if (out.problem.empty() && error.empty() && out.hasBlobs)
    out.problem = checkColumns(db, "blobs",
                               {{"key", "TEXT"}, {"part", "INTEGER"}, {"hash", "TEXT"}, {"data", "BLOB"}}, error);
  return out;
}

std::vector<std::string> danglingBlobKeys(SqliteDb& db, const SceneState& state, std::string& error) {
  std::vector<std::string> out;
  const std::set<std::string> cells = foliageCellKeys(state);
  std::set<std::string> ocioKeys;
  for (const OcioFile& f : state.settings.post.ocioConfig.files) ocioKeys.insert(ocioBlobKey(f.contentHash));
  SqliteStmt q(db, "SELECT DISTINCT key FROM blobs ORDER BY key");
  while (q.step(error)) {
    const std::string key = q.text(0);
    if (const auto id = idAfter(key, "mesh/"); id && state.assets.count(AssetId(*id))) continue;
    if (const auto id = idAfter(key, "terrain/"); id && state.terrains.count(TerrainId(*id))) continue;
    if (cells.count(key)) continue;  // a foliage cell (foliage_file.h)
    if (key.rfind("clusters/", 0) == 0) continue;  // cluster blobs: cluster_file.h accounts for them
    if (!state.settings.post.lut.empty() && key == lutBlobKey(state.settings.post.lut.contentHash)) continue;
    if (ocioKeys.count(key)) continue;  // a file of the OpenColorIO config (ocio_config.h)
    // A standalone texture's bytes (format 5; a mesh's textures live in its mesh blob).
    if (const auto id = idAfter(key, "texture/"); id) {
      const TextureAsset* t = state.findTexture(TextureId(*id));
      if (t && t->standalone()) continue;
    }
    out.push_back(key);
  }
  return out;
}

}  // namespace hs::scene
