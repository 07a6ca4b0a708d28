#include "mesh/tileset_reader.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <cctype>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/json.h"
#include "mesh/gltf_geometry.h"
#include "mesh/implicit_tiling.h"

namespace hs::mesh {
namespace fs = std::filesystem;
namespace {

// A content or tileset file is read whole; larger ones are refused (glTF
// itself stops at 2 GB).
constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;

bool readBytes(const fs::path& path, std::vector<uint8_t>& out, std::string& problem) {
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) {
    problem = fs::exists(path, ec) ? "cannot be read" : "is missing";
    return false;
  }
  if (size > kMaxFileBytes) {
    problem = "is larger than 2 GB";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out.resize(size);
  if (!in || !in.read(reinterpret_cast<char*>(out.data()), std::streamsize(size))) {
    problem = "cannot be read";
    return false;
  }
  return true;
}

// The first `n` bytes of `path` (fewer when it is shorter) and its size.
bool peekBytes(const fs::path& path, size_t n, uint64_t& size, std::string& head, std::string& problem) {
  std::error_code ec;
  size = fs::file_size(path, ec);
  if (ec) {
    problem = fs::exists(path, ec) ? "cannot be read" : "is missing";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  head.assign(n, '\0');
  if (!in) {
    problem = "cannot be read";
    return false;
  }
  in.read(head.data(), std::streamsize(n));
  head.resize(size_t(in.gcount()));
  return true;
}

uint32_t le32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

bool finiteNumber(const Json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

// The rotation 3D Tiles puts between a glTF's up axis and the tileset's z.
glm::dmat4 upAxisToZ(const std::string& up) {
  glm::dmat4 m(1.0);
  if (up == "Z") return m;
  if (up == "X") {  // (x, y, z) -> (-z, y, x)
    m[0] = {0, 0, 1, 0};
    m[2] = {-1, 0, 0, 0};
    return m;
  }
  m[1] = {0, 0, 1, 0};   // y -> z
  m[2] = {0, -1, 0, 0};  // z -> -y
  return m;
}

std::string shortName(const fs::path& p) { return p.string(); }

struct Reader {
  Tileset& out;
  const Progress* progress;
  std::vector<fs::path> stack;  // tilesets being read, outermost first (cycles)
  size_t contentsDone = 0;
  int cmptDepth = 0;  // composites being read inside each other
  static constexpr int kMaxCmptNesting = 8;
  // Implicit tiles expanded so far: a constant availability of 1 over deep
  // levels names more tiles than any tileset has; beyond this the rest of
  // every implicit tree is left out (said once).
  // Set by readTilesetTree: binary and glTF contents are listed here, not decoded.
  std::vector<TilesetContentRef>* listed = nullptr;
  size_t implicitTiles = 0;
  bool implicitCapped = false;
  static constexpr size_t kMaxImplicitTiles = size_t(1) << 20;

  void warn(std::string text) { out.warnings.push_back(std::move(text)); }

  // One content: its triangles appended to `tile`, placed by `world`.
  // True when something came in (triangles, or an external tileset's tiles).
  bool content(const fs::path& file, const std::vector<uint8_t>& bytes, const glm::dmat4& world,
               const std::string& upAxis, TilesetTile& tile, int tileIndex, int depth) {
    const std::string what = shortName(file);
    auto glb = [&](const std::vector<uint8_t>& g, glm::dvec3 rtc) {
      GltfGeometry geo;
      std::string error;
      if (!readGltfGeometry(g, file.parent_path().string(), what, geo, error)) {
        warn(error + "; its tile is left empty");
        return false;
      }
      for (auto& w : geo.warnings) warn(std::move(w));
      if (geo.rtcCenter) rtc += *geo.rtcCenter;
      const glm::dmat4 m = world * glm::translate(glm::dmat4(1.0), rtc) * upAxisToZ(upAxis);
      const uint32_t first = uint32_t(tile.positions.size());
      const bool uvsBefore = tile.positions.empty() || !tile.uvs.empty();
      for (const glm::dvec3& p : geo.positions) tile.positions.emplace_back(m * glm::dvec4(p, 1.0));
      if (uvsBefore && !geo.uvs.empty()) tile.uvs.insert(tile.uvs.end(), geo.uvs.begin(), geo.uvs.end());
      else tile.uvs.clear();
      for (uint32_t i : geo.indices) tile.indices.push_back(first + i);
      out.trianglesDeclared += geo.declaredTriangles;
      return true;
    };
    const std::string magic = bytes.size() >= 4 ? std::string(reinterpret_cast<const char*>(bytes.data()), 4) : "";
    bool read = false;
    if (magic == "glTF") {
      read = glb(bytes, glm::dvec3(0.0));
    } else if (magic == "b3dm") {
      if (bytes.size() < 28 || le32(&bytes[8]) > bytes.size() || le32(&bytes[8]) < 28) {
        warn(what + ": a b3dm whose header is truncated or names more bytes than the file has; its tile is left empty");
        return false;
      }
      const uint64_t total = le32(&bytes[8]), ftJson = le32(&bytes[12]), ftBin = le32(&bytes[16]),
                     btJson = le32(&bytes[20]), btBin = le32(&bytes[24]);
      const uint64_t glbAt = 28 + ftJson + ftBin + btJson + btBin;
      if (glbAt + 12 > total) {
        warn(what + ": its b3dm tables run past its " + std::to_string(total) +
             " bytes (a legacy b3dm header?); its tile is left empty");
        return false;
      }
      glm::dvec3 rtc(0.0);
      if (ftJson > 0) {
        std::string perr;
        const std::string text(reinterpret_cast<const char*>(&bytes[28]), size_t(ftJson));
        std::optional<Json> ft = parseJson(text.substr(0, text.find_last_not_of(' ') + 1), perr);
        if (!ft) {
          warn(what + ": its b3dm feature table is not JSON (" + perr + "); read without it");
        } else if (ft->contains("RTC_CENTER")) {
          const Json& c = (*ft)["RTC_CENTER"];
          if (c.is_array() && c.size() == 3 && finiteNumber(c[0]) && finiteNumber(c[1]) && finiteNumber(c[2])) {
            rtc = {c[0].get<double>(), c[1].get<double>(), c[2].get<double>()};
          } else if (c.is_object() && c.contains("byteOffset") && c["byteOffset"].is_number_unsigned() &&
                     ftBin >= 24 && c["byteOffset"].get<uint64_t>() <= ftBin - 24) {  // no wrap-around
            const uint8_t* p = &bytes[28 + ftJson + c["byteOffset"].get<uint64_t>()];
            double v[3];
            std::memcpy(v, p, 24);
            rtc = {v[0], v[1], v[2]};
          } else {
            warn(what + ": its RTC_CENTER is not three numbers; ignored");
          }
        }
      }
      read = glb(std::vector<uint8_t>(bytes.begin() + long(glbAt), bytes.begin() + long(total)), rtc);
    } else if (magic == "cmpt") {
      // A composite: inner tiles one after another, each with its own header.
      // Composites inside composites are allowed; a file nesting them deeper
      // than any exporter does is refused rather than recursed into.
      if (cmptDepth >= kMaxCmptNesting) {
        warn(what + ": cmpt tiles nested more than " + std::to_string(kMaxCmptNesting) + " deep; the rest skipped");
        return false;
      }
      if (bytes.size() < 16) {
        warn(what + ": a truncated cmpt header; its tile is left empty");
        return false;
      }
      const uint64_t total = std::min<uint64_t>(le32(&bytes[8]), bytes.size());
      const uint32_t count = le32(&bytes[12]);
      uint64_t at = 16;
      bool any = false;
      for (uint32_t i = 0; i < count; ++i) {
        if (at + 12 > total || le32(&bytes[at + 8]) < 12 || at + le32(&bytes[at + 8]) > total) {
          warn(what + ": inner tile " + std::to_string(i) + " of its cmpt runs past the file; the rest skipped");
          break;
        }
        const uint32_t len = le32(&bytes[at + 8]);
        ++cmptDepth;
        any = content(file, std::vector<uint8_t>(bytes.begin() + long(at), bytes.begin() + long(at + len)), world,
                      upAxis, tile, tileIndex, depth) || any;
        --cmptDepth;
        at += len;
      }
      return any;
    } else if (magic == "pnts" || magic == "i3dm" || magic == "vctr" || magic == "geom") {
      warn(what + ": " + magic + " content (" +
           (magic == "pnts" ? "points" : magic == "i3dm" ? "instanced models" : "vector data") +
           ") is not read: a cluster hierarchy holds triangles");
      return false;
    } else if (cmptDepth == 0 && !bytes.empty() && (bytes[0] == '{' || bytes[0] == ' ' || bytes[0] == '\n')) {
      // JSON: an external tileset, or a glTF asset (never inside a cmpt,
      // whose inner tiles are binary with headers).
      std::string perr;
      std::optional<Json> j = parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), perr);
      if (!j) {
        warn(what + ": not JSON (" + perr + "); its tile is left empty");
        return false;
      }
      if (j->is_object() && j->contains("root")) {
        tileset(file, *j, world, tileIndex, depth + 1);
        return true;
      }
      read = glb(bytes, glm::dvec3(0.0));
    } else {
      std::string shown;
      for (size_t i = 0; i < std::min<size_t>(4, bytes.size()); ++i)
        shown += std::isprint(bytes[i]) ? char(bytes[i]) : '?';
      warn(what + ": an unknown tile format (it starts with \"" + shown + "\", not b3dm, glTF, cmpt or JSON); its tile is "
           "left empty");
      return false;
    }
    if (read) {
      ++out.contentsRead;
      if (!tile.content.empty()) tile.content += ", ";
      tile.content += what;
    }
    return read;
  }

  void contentUri(const fs::path& base, const Json& c, const glm::dmat4& world, const std::string& upAxis,
                  TilesetTile& tile, int tileIndex, int depth, const std::string& where) {
    const char* key = c.contains("uri") ? "uri" : "url";  // "url" before 1.0
    if (!c.is_object() || !c.contains(key) || !c[key].is_string()) {
      warn(shortName(base) + ": " + where + ".content has no uri; skipped");
      tile.contentMissing = true;
      return;
    }
    std::string uri = c[key].get<std::string>();
    if (uri.rfind("data:", 0) == 0) {
      warn(shortName(base) + ": " + where + ": a data: URI content is not read");
      tile.contentMissing = true;
      return;
    }
    if (auto q = uri.find_first_of("?#"); q != std::string::npos) uri.resize(q);
    ++out.contentsDeclared;
    const fs::path file = base.parent_path() / uri;
    if (isCancelled(progress)) return;
    reportProgress(progress, 1.0 - 1.0 / (1.0 + 0.02 * double(++contentsDone)), "reading tiles");
    // A tileset named again while it is being read: a cycle.
    std::error_code ec;
    const fs::path canon = fs::weakly_canonical(file, ec);
    for (const fs::path& open : stack)
      if (!ec && open == canon) {
        std::string chain;
        for (const fs::path& s : stack) chain += s.filename().string() + " -> ";
        warn(shortName(base) + ": " + where + " names " + uri + ", a tileset already being read (cycle: " + chain +
             canon.filename().string() + "); not followed");
        tile.contentMissing = true;
        return;
      }
    std::vector<uint8_t> bytes;
    std::string problem;
    auto unreadable = [&] {
      warn(shortName(file) + " (content of " + where + " in " + shortName(base) + ") " + problem +
           "; its tile is left empty");
      tile.contentMissing = true;
    };
    if (listed) {
      // Listing the tree: the first bytes tell what a content is. An
      // external tileset is part of the tree (read now); triangles are listed.
      uint64_t size = 0;
      std::string magic;
      if (!peekBytes(file, 4, size, magic, problem)) {
        return unreadable();
      }
      const bool json = !magic.empty() && (magic[0] == '{' || magic[0] == ' ' || magic[0] == '\n');
      bool listIt = magic == "glTF" || magic == "b3dm" || magic == "cmpt";
      if (json) {
        if (!readBytes(file, bytes, problem)) {
          return unreadable();
        }
        std::string perr;
        const std::optional<Json> j =
            parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), perr);
        listIt = j && j->is_object() && !j->contains("root");  // a glTF asset in JSON
      }
      if (listIt) {
        listed->push_back({tileIndex, file.string(), where + " in " + shortName(base), world, upAxis, size});
        return;
      }
      // An external tileset, or what content() names as unreadable.
    }
    if (bytes.empty() && !readBytes(file, bytes, problem)) {
      return unreadable();
    }
    if (!content(file, bytes, world, upAxis, tile, tileIndex, depth)) tile.contentMissing = true;
  }

  // Contents may append tiles (an external tileset's root becomes a child),
  // so tile `index` is filled through a copy and put back.
  template <class Fill>
  void fillTile(int index, Fill&& fill) {
    TilesetTile filled = out.tiles[size_t(index)];
    fill(filled);
    TilesetTile& into = out.tiles[size_t(index)];
    std::swap(into.positions, filled.positions);
    std::swap(into.uvs, filled.uvs);
    std::swap(into.indices, filled.indices);
    into.content = filled.content;
    into.contentMissing = filled.contentMissing;
  }

  // An implicit tree (mesh/implicit_tiling.h): tile `t` is its root, level
  // 0. Its tiles become explicit tiles in depth-first order, children in
  // Morton order; each level's geometric error is half the one above, its
  // refinement and transform the root's; contents come from the root's
  // content templates where the subtree says they are available.
  struct Implicit {
    const fs::path& base;
    std::vector<Json> contents;  // the root's content objects, uri a template
    const glm::dmat4& world;
    const ImplicitScheme& scheme;
    const TilesetTile& root;     // parent, refinement and level-0 error
    const std::string& upAxis;
    const std::string& where;
    int depth;
  };

  void implicitTree(const fs::path& base, const Json& t, const glm::dmat4& world, const TilesetTile& root,
                    const ImplicitScheme& scheme, const std::string& upAxis, const std::string& where, int depth) {
    Implicit walk{base, {}, world, scheme, root, upAxis, where, depth};
    if (t.contains("content")) walk.contents.push_back(t["content"]);
    if (t.contains("contents") && t["contents"].is_array())
      for (const Json& c : t["contents"]) walk.contents.push_back(c);
    implicitSubtree(walk, 0, 0, 0, 0, root.parent);
  }

  static std::string implicitName(int dims, int level, uint64_t x, uint64_t y, uint64_t z) {
    return std::to_string(level) + "/" + std::to_string(x) + "/" + std::to_string(y) +
           (dims == 3 ? "/" + std::to_string(z) : "");
  }

  // The subtree whose root is tile (level, x, y, z), hung under `parent`.
  void implicitSubtree(const Implicit& w, int level, uint64_t x, uint64_t y, uint64_t z, int parent) {
    if (isCancelled(progress)) return;
    const std::string uri = expandImplicitUri(w.scheme.subtreeUri, level, x, y, z);
    const fs::path file = w.base.parent_path() / uri;
    std::vector<uint8_t> bytes;
    std::string problem;
    Subtree sub;
    const bool readable = readBytes(file, bytes, problem);
    if (!readable || !readSubtree(file, bytes, w.scheme, w.contents.size(), readBytes, sub, problem)) {
      // What lies below is unknown: a tile that did not come in stands for
      // it, so the tile above is not refined into a hole.
      warn(shortName(file) + " (subtree " + implicitName(w.scheme.dims, level, x, y, z) + " of " + w.where + " in " +
           shortName(w.base) + ")" + (readable ? ": " : " ") + problem + "; the tiles below it are left out");
      TilesetTile missing = w.root;
      missing.parent = parent;
      missing.geometricError = std::ldexp(w.root.geometricError, -level);
      missing.contentMissing = true;
      out.tiles.push_back(std::move(missing));
      return;
    }
    implicitTile(w, sub, 0, 0, 0, 0, level, x, y, z, parent);
  }

  // Tile (level, x, y, z), at `local` levels and (lx, ly, lz) below its subtree's root.
  void implicitTile(const Implicit& w, const Subtree& sub, int local, uint64_t lx, uint64_t ly, uint64_t lz,
                    int level, uint64_t x, uint64_t y, uint64_t z, int parent) {
    if (isCancelled(progress) || implicitCapped) return;
    const int dims = w.scheme.dims;
    const uint64_t bit = levelOffset(dims, local) + mortonIndex(dims, lx, ly, lz);
    if (!sub.tiles.at(bit)) return;
    if (++implicitTiles > kMaxImplicitTiles) {
      implicitCapped = true;
      warn(shortName(w.base) + ": " + w.where + ": implicit tiling makes more than " +
           std::to_string(kMaxImplicitTiles) + " tiles available; the rest are left out");
      return;
    }
    TilesetTile tile = w.root;
    tile.parent = parent;
    tile.geometricError = std::ldexp(w.root.geometricError, -level);
    const int index = int(out.tiles.size());
    out.tiles.push_back(std::move(tile));
    const std::string name = implicitName(dims, level, x, y, z);
    fillTile(index, [&](TilesetTile& filled) {
      for (size_t i = 0; i < w.contents.size(); ++i) {
        if (!sub.contents[i].at(bit)) continue;
        Json c = w.contents[i];
        const char* key = c.is_object() && c.contains("uri") ? "uri" : "url";
        if (c.is_object() && c.contains(key) && c[key].is_string())
          c[key] = expandImplicitUri(c[key].get<std::string>(), level, x, y, z);
        contentUri(w.base, c, w.world, w.upAxis, filled, index, w.depth + level,
                   w.where + " (implicit tile " + name + (w.contents.size() > 1 ? ", content " + std::to_string(i) : "") +
                       ")");
      }
    });
    if (level + 1 >= w.scheme.availableLevels) return;
    for (uint64_t c = 0; c < (uint64_t(1) << dims); ++c) {
      const uint64_t cx = c & 1u, cy = (c >> 1) & 1u, cz = (c >> 2) & 1u;
      if (local + 1 < w.scheme.subtreeLevels)
        implicitTile(w, sub, local + 1, 2 * lx + cx, 2 * ly + cy, 2 * lz + cz, level + 1, 2 * x + cx, 2 * y + cy,
                     2 * z + cz, index);
      else if (sub.childSubtrees.at(mortonIndex(dims, 2 * lx + cx, 2 * ly + cy, 2 * lz + cz)))
        implicitSubtree(w, level + 1, 2 * x + cx, 2 * y + cy, 2 * z + cz, index);
    }
  }

  // Tile `t` of tileset file `base` (JSON path `where`) under `parent`.
  void tileNode(const fs::path& base, const Json& t, const glm::dmat4& parentWorld, int parent, bool parentAdds,
                const std::string& upAxis, const std::string& where, int depth) {
    if (isCancelled(progress)) return;
    if (depth > 256) {
      warn(shortName(base) + ": " + where + ": tiles nested deeper than 256; not read");
      return;
    }
    if (!t.is_object()) {
      warn(shortName(base) + ": " + where + " is not a tile object; skipped");
      return;
    }
    glm::dmat4 world = parentWorld;
    if (t.contains("transform")) {
      const Json& m = t["transform"];
      bool ok = m.is_array() && m.size() == 16;
      for (size_t i = 0; ok && i < 16; ++i) ok = finiteNumber(m[i]);
      if (ok) {
        glm::dmat4 local;
        for (int i = 0; i < 16; ++i) local[i / 4][i % 4] = m[size_t(i)].get<double>();  // column-major
        world = parentWorld * local;
      } else {
        warn(shortName(base) + ": " + where + ".transform is not 16 finite numbers; ignored");
      }
    }
    TilesetTile tile;
    tile.parent = parent;
    tile.additive = parentAdds;
    if (t.contains("refine")) {
      const std::string r = t["refine"].is_string() ? t["refine"].get<std::string>() : "";
      if (r == "ADD" || r == "add") tile.additive = true;
      else if (r == "REPLACE" || r == "replace") tile.additive = false;
      else warn(shortName(base) + ": " + where + ".refine is neither ADD nor REPLACE; its parent's is used");
    }
    if (t.contains("geometricError") && finiteNumber(t["geometricError"]) && t["geometricError"].get<double>() >= 0.0) {
      tile.geometricError = t["geometricError"].get<double>();
    } else {
      tile.geometricError = parent >= 0 ? out.tiles[size_t(parent)].geometricError : 0.0;
      warn(shortName(base) + ": " + where + ".geometricError is missing or not a non-negative number; " +
           (parent >= 0 ? "its parent's" : "0") + " is used");
    }
    ImplicitScheme scheme;
    std::string implicitProblem;
    if (parseImplicitTiling(t, scheme, implicitProblem)) {
      implicitTree(base, t, world, tile, scheme, upAxis, where, depth);
      if (t.contains("children"))
        warn(shortName(base) + ": " + where + " has both implicit tiling and children (3D Tiles forbids it); the "
             "children are ignored");
      return;
    }
    if (!implicitProblem.empty()) {
      // Its content names a template nobody can expand without the scheme.
      warn(shortName(base) + ": " + where + ".implicitTiling: " + implicitProblem +
           "; its implicit tree is left out and the tile is kept empty");
      tile.contentMissing = true;
      out.tiles.push_back(std::move(tile));
      return;
    }
    const int index = int(out.tiles.size());
    out.tiles.push_back(std::move(tile));
    fillTile(index, [&](TilesetTile& filled) {
      if (t.contains("content"))
        contentUri(base, t["content"], world, upAxis, filled, index, depth, where);
      if (t.contains("contents") && t["contents"].is_array())
        for (size_t i = 0; i < t["contents"].size(); ++i)
          contentUri(base, t["contents"][i], world, upAxis, filled, index, depth,
                     where + ".contents[" + std::to_string(i) + "]");
    });
    if (t.contains("children")) {
      const Json& c = t["children"];
      if (!c.is_array()) {
        warn(shortName(base) + ": " + where + ".children is not an array; ignored");
      } else {
        for (size_t i = 0; i < c.size(); ++i)
          tileNode(base, c[i], world, index, out.tiles[size_t(index)].additive, upAxis,
                   where + ".children[" + std::to_string(i) + "]", depth + 1);
      }
    }
  }

  // A whole tileset file (the top one, or an external one whose root hangs
  // under tile `parent`).
  void tileset(const fs::path& file, const Json& doc, const glm::dmat4& world, int parent, int depth) {
    std::error_code ec;
    stack.push_back(fs::weakly_canonical(file, ec));
    ++out.tilesetFiles;
    std::string upAxis = "Y";
    if (doc.contains("asset") && doc["asset"].is_object()) {
      const Json& a = doc["asset"];
      if (a.contains("gltfUpAxis") && a["gltfUpAxis"].is_string()) upAxis = a["gltfUpAxis"].get<std::string>();
      const std::string v = a.contains("version") && a["version"].is_string() ? a["version"].get<std::string>() : "";
      if (out.version.empty()) out.version = v;
      if (v != "1.0" && v != "1.1" && v != "0.0")
        warn(shortName(file) + ": asset.version \"" + v + "\" (this reader knows 1.0 and 1.1); read as 1.1");
    } else {
      warn(shortName(file) + ": it has no asset object; read as 3D Tiles 1.1");
    }
    const bool adds = parent >= 0 && out.tiles[size_t(parent)].additive;
    tileNode(file, doc["root"], world, parent, adds, upAxis, "root", depth);
    stack.pop_back();
  }
};

}  // namespace

bool isTilesetFile(const std::string& path) {
  const fs::path p(path);
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".json") return false;
  std::vector<uint8_t> bytes;
  std::string problem;
  if (!readBytes(p, bytes, problem)) return true;  // a .json named for import: let the reader say what is wrong
  std::string perr;
  const std::optional<Json> j = parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), perr);
  return !j || (j->is_object() && j->contains("root"));
}

namespace {

// The top tileset.json parsed; false with `error` naming it.
std::optional<Json> topTileset(const std::string& path, std::string& error) {
  std::vector<uint8_t> bytes;
  std::string problem;
  if (!readBytes(path, bytes, problem)) {
    error = path + ": the tileset " + problem;
    return std::nullopt;
  }
  std::string perr;
  std::optional<Json> doc = parseJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), perr);
  if (!doc) {
    error = path + ": not a tileset: " + perr;
    return std::nullopt;
  }
  if (!doc->is_object() || !doc->contains("root") || !(*doc)["root"].is_object()) {
    error = path + ": not a 3D Tiles tileset (no \"root\" tile)";
    return std::nullopt;
  }
  return doc;
}

// The first warnings, on one line (the CLI escapes line breaks in a
// message: file names could carry terminal controls).
std::string firstWarnings(const std::vector<std::string>& warnings) {
  constexpr size_t kShown = 8;
  std::string out;
  for (size_t i = 0; i < warnings.size() && i < kShown; ++i) out += (i ? "; " : ": ") + warnings[i];
  if (warnings.size() > kShown) out += "; and " + std::to_string(warnings.size() - kShown) + " more";
  return out;
}

}  // namespace

bool readTilesetTree(const std::string& path, Tileset& out, std::vector<TilesetContentRef>& contents,
                     std::string& error, const Progress* progress) {
  out = Tileset{};
  contents.clear();
  const std::optional<Json> doc = topTileset(path, error);
  if (!doc) return false;
  Reader r{out, progress, {}};
  r.listed = &contents;
  r.tileset(fs::path(path), *doc, glm::dmat4(1.0), -1, 0);
  if (isCancelled(progress)) return false;
  if (contents.empty()) {
    error = path + ": no triangles came in (none of its " + std::to_string(out.contentsDeclared) +
            " contents can hold any)" + firstWarnings(out.warnings);
    return false;
  }
  return true;
}

bool readTilesetContent(const TilesetContentRef& ref, TilesetTile& into, Tileset& log) {
  std::vector<uint8_t> bytes;
  std::string problem;
  if (!readBytes(ref.file, bytes, problem)) {
    log.warnings.push_back(ref.file + " (content of " + ref.where + ") " + problem + "; its tile is left empty");
    into.contentMissing = true;
    return false;
  }
  Reader r{log, nullptr, {}};
  const bool read = r.content(ref.file, bytes, ref.world, ref.upAxis, into, ref.tile, 0);
  if (!read) into.contentMissing = true;
  return read;
}

bool readTileset(const std::string& path, Tileset& out, std::string& error, const Progress* progress) {
  out = Tileset{};
  const std::optional<Json> doc = topTileset(path, error);
  if (!doc) return false;
  Reader r{out, progress, {}};
  r.tileset(fs::path(path), *doc, glm::dmat4(1.0), -1, 0);
  if (isCancelled(progress)) return false;
  size_t triangles = 0;
  for (const TilesetTile& t : out.tiles) triangles += t.indices.size() / 3;
  if (triangles == 0) {
    error = path + ": no triangles came in (" + std::to_string(out.contentsRead) + " of " +
            std::to_string(out.contentsDeclared) + " contents read)" + firstWarnings(out.warnings);
    return false;
  }
  return true;
}

}  // namespace hs::mesh
