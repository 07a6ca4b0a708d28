#include "cli/terrain_info.h"

#include <cstdio>

namespace hs::cli {
namespace {

Json arr2(const glm::dvec2& v) { return Json::array({v.x, v.y}); }
Json arr3(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

}  // namespace

Json terrainInfoJson(const scene::SceneState& s) {
  Json out = Json::array();
  for (scene::EntityId id : scene::terrainEntities(s, false)) {
    const scene::TerrainAsset& t = *scene::terrainOf(s, id);
    const terrain::Terrain& tr = t.data->terrain();
    const terrain::Heightfield& hf = tr.height;
    const terrain::HeightRange r = hf.range();
    Json o = Json::object();
    o["name"] = t.name;
    o["entity"] = id;
    o["entity_name"] = s.find(id)->name;
    o["terrain_id"] = t.id;
    o["samples"] = Json::array({hf.samplesX(), hf.samplesY()});
    o["size_m"] = arr2(hf.sizeMetres());
    o["spacing_m"] = arr2(hf.spacing());
    o["origin"] = arr3(hf.origin());
    o["world_origin"] = arr3(scene::terrainWorldOrigin(s, id));
    o["height_range_m"] = Json::array({double(r.min), double(r.max)});
    Json crs = Json::object();
    crs["name"] = hf.geo().crsName;
    crs["epsg"] = hf.geo().epsg;
    crs["georeferenced"] = hf.geo().valid();
    o["crs"] = std::move(crs);
    Json layers = Json::array();
    for (const auto& m : t.materials) layers.push_back(m.name);
    o["layers"] = std::move(layers);
    o["paint_rules"] = t.paintRules.size();
    o["hole_tiles"] = hf.holes().allocatedTiles();
    o["tiles"] = Json::array({hf.heights().tilesX(), hf.heights().tilesY()});
    o["memory_bytes"] = tr.memoryBytes();
    o["lod_error_px"] = s.find(id)->terrain->lodErrorPixels;
    out.push_back(std::move(o));
  }
  return out;
}

void printTerrainInfo(const scene::SceneState& s) {
  const auto ids = scene::terrainEntities(s, false);
  if (ids.empty()) return;
  std::printf("terrains:\n");
  for (scene::EntityId id : ids) {
    const scene::TerrainAsset& t = *scene::terrainOf(s, id);
    const terrain::Heightfield& hf = t.data->heights();
    const terrain::HeightRange r = hf.range();
    const glm::dvec3 o = scene::terrainWorldOrigin(s, id);
    std::printf("  %s: %.3f x %.3f m, %d x %d samples (spacing %.4g x %.4g m), heights %.2f..%.2f m, origin %.3f, %.3f, %.3f, "
                "CRS %s, %zu layers\n",
                t.name.c_str(), hf.sizeMetres().x, hf.sizeMetres().y, hf.samplesX(), hf.samplesY(), hf.spacing().x,
                hf.spacing().y, double(r.min), double(r.max), o.x, o.y, o.z,
                hf.geo().valid() ? (hf.geo().crsName + (hf.geo().epsg ? " (EPSG:" + std::to_string(hf.geo().epsg) + ")" : ""))
                                       .c_str()
                                 : "none (local)",
                t.materials.size());
  }
}

}  // namespace hs::cli
