#include "mesh/tileset_writer.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "core/json.h"
#include "mesh/export/export_geometry.h"

namespace hs::mesh {
namespace fs = std::filesystem;
namespace {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
  bool empty() const { return lo.x > hi.x; }
  void add(const glm::dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void add(const Box& b) {
    if (!b.empty()) add(b.lo), add(b.hi);
  }
};

// 3D Tiles' "box": centre, then the three half-axes (here axis-aligned).
Json boxJson(const Box& b) {
  const glm::dvec3 c = 0.5 * (b.lo + b.hi), h = glm::max(0.5 * (b.hi - b.lo), glm::dvec3(1e-3));
  return Json::array({c.x, c.y, c.z, h.x, 0.0, 0.0, 0.0, h.y, 0.0, 0.0, 0.0, h.z});
}

}  // namespace

ExportResult writeTileset(const std::vector<TileToWrite>& tiles, const std::string& path,
                          const TilesetWriteOptions& options, const Progress* progress) {
  ExportResult r;
  if (tiles.empty() || tiles.front().parent != -1) {
    r.error = path + ": a tileset needs a root tile";
    return r;
  }
  const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  std::error_code ec;
  const bool madeTilesDir = !fs::exists(dir / "tiles", ec);
  fs::create_directories(dir / "tiles", ec);
  if (ec) {
    r.error = path + ": cannot make " + (dir / "tiles").string() + " (" + ec.message() + ")";
    return r;
  }
  auto giveUp = [&] {
    if (madeTilesDir) fs::remove(dir / "tiles", ec);  // only when empty: nothing of ours was renamed in
  };
  // Boxes from the leaves up: each holds its content and its children's.
  std::vector<Box> boxes(tiles.size());
  std::vector<std::vector<size_t>> children(tiles.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    const MeshData& m = tiles[i].content;
    for (uint32_t v : m.indices) boxes[i].add(m.origin + glm::dvec3(m.positions[v]));
    if (i > 0) {
      if (tiles[i].parent < 0 || size_t(tiles[i].parent) >= i) {
        r.error = path + ": tile " + std::to_string(i) + " does not come after its parent";
        giveUp();
        return r;
      }
      children[size_t(tiles[i].parent)].push_back(i);
    }
  }
  for (size_t i = tiles.size(); i-- > 1;) boxes[size_t(tiles[i].parent)].add(boxes[i]);
  exporting::PendingFiles files;
  std::vector<std::string> contentUri(tiles.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    if (isCancelled(progress)) {
      giveUp();
      return r;
    }
    reportProgress(progress, double(i) / double(tiles.size()), "Writing tiles");
    const MeshData& m = tiles[i].content;
    if (m.indices.empty()) continue;
    ExportOptions o;
    o.format = ExportFormat::Glb;
    o.world = true;  // the tile's origin into its node's translation; floats about it
    o.dracoBits = options.dracoBits;
    const exporting::Geometry g = exporting::placeGeometry(m, o, true);
    contentUri[i] = "tiles/" + std::to_string(i) + ".glb";
    double moved = 0.0;
    if (!exporting::writeGlb(m, g, (dir / contentUri[i]).string(), o, files, nullptr, r.error, &moved)) {
      giveUp();
      return r;
    }
    r.quantizationError = std::max(r.quantizationError, moved);
    r.vertices += m.positions.size();
    r.triangles += m.indices.size() / 3;
  }
  // The tree, written from the leaves up (each tile's JSON holds its children's).
  std::vector<Json> json(tiles.size());
  for (size_t i = tiles.size(); i-- > 0;) {
    Json t = {{"boundingVolume", {{"box", boxJson(boxes[i])}}}, {"geometricError", tiles[i].geometricError}};
    if (i == 0) {
      t["refine"] = "REPLACE";
      if (options.rootTransform != glm::dmat4(1.0)) {
        Json m = Json::array();
        for (int c = 0; c < 4; ++c)
          for (int k = 0; k < 4; ++k) m.push_back(options.rootTransform[c][k]);
        t["transform"] = std::move(m);
      }
    }
    if (!contentUri[i].empty()) t["content"] = {{"uri", contentUri[i]}};
    if (!children[i].empty()) {
      Json c = Json::array();
      for (size_t k : children[i]) c.push_back(std::move(json[k]));
      t["children"] = std::move(c);
    }
    json[i] = std::move(t);
  }
  const Json tileset = {{"asset", {{"version", "1.1"}, {"generator", options.generator}}},
                        {"geometricError", std::max(options.tilesetError, tiles.front().geometricError)},
                        {"root", std::move(json[0])}};
  if (!files.add(path, writeJson(tileset, 1), r.error)) {
    giveUp();
    return r;
  }
  std::vector<std::string> written;
  if (!files.commit(written, r.error)) {
    giveUp();
    return r;
  }
  // tileset.json first in the list.
  r.written.push_back(written.back());
  written.pop_back();
  r.written.insert(r.written.end(), written.begin(), written.end());
  return r;
}

}  // namespace hs::mesh
