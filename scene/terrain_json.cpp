#include "scene/terrain_json.h"

#include <cmath>

#include <QByteArray>

#include "core/content_hash.h"

namespace hs::scene {
namespace {

Json vec2Json(const glm::dvec2& v) { return Json::array({v.x, v.y}); }
Json vec3Json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

Json materialJson(const terrain::Material& m) {
  Json o = Json::object();
  o["name"] = m.name;
  o["albedo"] = Json::array({double(m.albedo.x), double(m.albedo.y), double(m.albedo.z)});
  o["albedo_texture"] = m.albedoTexture;
  o["normal_texture"] = m.normalTexture;
  o["roughness"] = double(m.roughness);
  o["tiling_m"] = double(m.tilingMetres);
  return o;
}

Json ruleJson(const terrain::PaintRule& r) {
  Json o = Json::object();
  o["layer"] = r.layer;
  o["enabled"] = r.enabled;
  o["use_altitude"] = r.useAltitude;
  o["altitude_min"] = r.altitudeMin;
  o["altitude_max"] = r.altitudeMax;
  o["altitude_blend"] = r.altitudeBlend;
  o["use_slope"] = r.useSlope;
  o["slope_min"] = r.slopeMin;
  o["slope_max"] = r.slopeMax;
  o["slope_blend"] = r.slopeBlend;
  o["strength"] = double(r.strength);
  return o;
}

// Members that must be there.
bool needNumber(JsonReader& r, const Json& obj, const std::string& path, std::string_view key, double& out) {
  const Json* m = r.required(obj, path, key);
  return m && r.number(*m, jsonPath(path, key), out);
}
bool needNumbers(JsonReader& r, const Json& obj, const std::string& path, std::string_view key, double* out, size_t n,
                 const char* shape) {
  const Json* m = r.required(obj, path, key);
  return m && r.numbers(*m, jsonPath(path, key), out, n, shape);
}
template <class Int>
bool needInteger(JsonReader& r, const Json& obj, const std::string& path, std::string_view key, Int& out, Int lo,
                 Int hi) {
  const Json* m = r.required(obj, path, key);
  return m && r.integer(*m, jsonPath(path, key), out, lo, hi);
}

bool readMaterial(JsonReader& r, const Json& v, const std::string& path, terrain::Material& m) {
  double c[3], rough = 0, tiling = 0;
  if (!r.object(v, path) || !r.optString(v, path, "name", m.name) ||
      !needNumbers(r, v, path, "albedo", c, 3, "[r, g, b]") || !needNumber(r, v, path, "roughness", rough) ||
      !needNumber(r, v, path, "tiling_m", tiling) || !r.optString(v, path, "albedo_texture", m.albedoTexture) ||
      !r.optString(v, path, "normal_texture", m.normalTexture))
    return false;
  if (!(tiling > 0.0)) return r.fail(jsonPath(path, "tiling_m"), "must be positive");
  m.albedo = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
  m.roughness = float(std::clamp(rough, 0.0, 1.0));
  m.tilingMetres = float(tiling);
  return true;
}

bool readRule(JsonReader& r, const Json& v, const std::string& path, terrain::PaintRule& rule, int layers) {
  double layer = 0, strength = 0;
  if (!r.object(v, path) || !needNumber(r, v, path, "layer", layer)) return false;
  if (layer < 0 || layer >= layers || layer != std::floor(layer))
    return r.fail(jsonPath(path, "layer"), "not a layer of this terrain (0.." + std::to_string(layers - 1) + ")");
  rule.layer = int(layer);
  if (!needNumber(r, v, path, "strength", strength) || !r.optBoolean(v, path, "enabled", rule.enabled) || !r.optBoolean(v, path, "use_altitude", rule.useAltitude) ||
      !r.optBoolean(v, path, "use_slope", rule.useSlope))
    return false;
  rule.strength = float(strength);
  for (auto [key, dst] : {std::pair{"altitude_min", &rule.altitudeMin}, {"altitude_max", &rule.altitudeMax},
                          {"altitude_blend", &rule.altitudeBlend}, {"slope_min", &rule.slopeMin},
                          {"slope_max", &rule.slopeMax}, {"slope_blend", &rule.slopeBlend}})
    if (!needNumber(r, v, path, key, *dst)) return false;
  return true;
}

bool readTerrain(JsonReader& r, const Json& o, const std::string& p, SceneState& state) {
  int64_t id = 0;
  int samples[2] = {0, 0}, layers = 0;
  double spacing[2], origin[3];
  if (!r.object(o, p) || !needInteger(r, o, p, "id", id, int64_t(1), int64_t(1) << 53)) return false;
  const std::string sp = jsonPath(p, "samples");
  const Json* s = r.required(o, p, "samples");
  double shape[2];
  if (!s || !r.numbers(*s, sp, shape, 2, "[x, y]")) return false;
  for (size_t k = 0; k < 2; ++k)
    if (!r.integer((*s)[k], jsonIndex(sp, k), samples[k], 0, 1000000)) return false;
  if (!needNumbers(r, o, p, "spacing_m", spacing, 2, "[x, y]") || !needNumbers(r, o, p, "origin", origin, 3, "[x, y, z]") ||
      !needInteger(r, o, p, "layers", layers, 1, terrain::kMaxPaintLayers))
    return false;
  if (!(spacing[0] > 0.0 && spacing[1] > 0.0)) return r.fail(jsonPath(p, "spacing_m"), "must be positive");
  TerrainAsset t;
  t.id = TerrainId(id);
  if (!r.optString(o, p, "name", t.name)) return false;
  const std::string mp = jsonPath(p, "materials");
  const Json* materials = r.required(o, p, "materials");
  if (!materials || !r.array(*materials, mp)) return false;
  if (materials->size() != size_t(layers)) return r.fail(mp, "expected one material per layer");
  for (size_t m = 0; m < materials->size(); ++m) {
    terrain::Material mat;
    if (!readMaterial(r, (*materials)[m], jsonIndex(mp, m), mat)) return false;
    t.materials.push_back(mat);
  }
  if (const Json* rules = JsonReader::member(o, "paint_rules");
      rules && !readPaintRules(r, *rules, jsonPath(p, "paint_rules"), layers, t.paintRules))
    return false;
  terrain::HeightfieldDesc d;
  d.samplesX = samples[0];
  d.samplesY = samples[1];
  d.sizeMetres = glm::dvec2(spacing[0], spacing[1]) * glm::dvec2(d.samplesX - 1, d.samplesY - 1);
  d.origin = glm::dvec3(origin[0], origin[1], origin[2]);
  if (const Json* crs = JsonReader::member(o, "crs")) {
    const std::string cp = jsonPath(p, "crs");
    if (!r.object(*crs, cp) || !r.optString(*crs, cp, "wkt", d.geo.crsWkt) ||
        !r.optString(*crs, cp, "name", d.geo.crsName) || !r.optInteger(*crs, cp, "epsg", d.geo.epsg, 0, 1 << 30))
      return false;
  }
  auto made = terrain::Terrain::create(d, t.materials);
  if (!made) return r.fail(p, made.error());
  made->height.setSpacing(glm::dvec2(spacing[0], spacing[1]));
  t.data = std::make_shared<TerrainData>(made.take());

  const std::string tp = jsonPath(p, "tiles");
  const Json* ts = r.required(o, p, "tiles");
  if (!ts || !r.object(*ts, tp)) return false;
  TerrainData::DescribedTiles described;
  std::string hash;
  const Json* h = r.required(*ts, tp, "content_hash");
  if (!h || !r.string(*h, jsonPath(tp, "content_hash"), hash)) return false;
  if (!fromHex(hash, described.contentHash))
    return r.fail(jsonPath(tp, "content_hash"), "expected a hexadecimal content hash, not '" + hash + "'");
  if (!r.optString(*ts, tp, "holes", described.holes)) return false;
  const std::string pp = jsonPath(tp, "paint");
  const Json* paint = r.required(*ts, tp, "paint");
  if (!paint || !r.array(*paint, pp)) return false;
  if (paint->size() != size_t(layers)) return r.fail(pp, "expected one entry per layer");
  for (size_t k = 0; k < paint->size(); ++k) {
    std::string bitmap;
    if (!r.string((*paint)[k], jsonIndex(pp, k), bitmap)) return false;
    described.paint.push_back(std::move(bitmap));
  }
  t.data->setDescribed(std::move(described));
  if (!state.terrains.emplace(t.id, std::move(t)).second) return r.fail(jsonPath(p, "id"), "duplicate terrain id");
  return true;
}

}  // namespace

Json paintRulesToJson(const std::vector<terrain::PaintRule>& rules) {
  Json a = Json::array();
  for (const auto& r : rules) a.push_back(ruleJson(r));
  return a;
}

bool readPaintRules(JsonReader& r, const Json& json, const std::string& path, int layers,
                    std::vector<terrain::PaintRule>& out) {
  out.clear();
  if (!r.array(json, path)) return false;
  for (size_t k = 0; k < json.size(); ++k) {
    terrain::PaintRule rule;
    if (!readRule(r, json[k], jsonIndex(path, k), rule, layers)) return false;
    out.push_back(rule);
  }
  return true;
}

std::string tileBitmap(const std::vector<bool>& present) {
  QByteArray bits(qsizetype((present.size() + 7) / 8), '\0');
  for (size_t i = 0; i < present.size(); ++i)
    if (present[i]) bits[qsizetype(i / 8)] = char(uint8_t(bits[qsizetype(i / 8)]) | uint8_t(1u << (i % 8)));
  return bits.toBase64().toStdString();
}

std::vector<bool> tileBitmapFromText(const std::string& text, size_t tiles, bool& ok) {
  std::vector<bool> out(tiles, false);
  const auto decoded = QByteArray::fromBase64Encoding(QByteArray::fromStdString(text),
                                                      QByteArray::AbortOnBase64DecodingErrors);
  ok = bool(decoded) && size_t(decoded.decoded.size()) == (tiles + 7) / 8;
  if (!ok) return out;
  for (size_t i = 0; i < tiles; ++i) out[i] = (uint8_t(decoded.decoded[qsizetype(i / 8)]) >> (i % 8)) & 1u;
  return out;
}

Json terrainsToJson(const SceneState& state) {
  Json out = Json::array();
  for (const auto& [id, t] : state.terrains) {
    if (!t.data) continue;
    const terrain::Terrain& tr = t.data->terrain();
    const terrain::Heightfield& hf = tr.height;
    Json o = Json::object();
    o["id"] = id;
    o["name"] = t.name;
    o["samples"] = Json::array({hf.samplesX(), hf.samplesY()});
    o["spacing_m"] = vec2Json(hf.spacing());
    o["size_m"] = vec2Json(hf.sizeMetres());
    o["origin"] = vec3Json(hf.origin());
    if (hf.geo().valid()) {
      Json crs = Json::object();
      crs["wkt"] = hf.geo().crsWkt;
      crs["name"] = hf.geo().crsName;
      crs["epsg"] = hf.geo().epsg;
      o["crs"] = std::move(crs);
    }
    o["layers"] = tr.paint.layerCount();
    Json materials = Json::array();
    for (const auto& m : t.materials) materials.push_back(materialJson(m));
    o["materials"] = std::move(materials);
    o["paint_rules"] = paintRulesToJson(t.paintRules);
    // Tile summary: which sparse tiles hold data, and the content of all.
    const int tiles = hf.heights().tileCount();
    Json ts = Json::object();
    ts["tile_size"] = terrain::kTileSize;
    ts["tiles"] = Json::array({hf.heights().tilesX(), hf.heights().tilesY()});
    if (const auto& d = t.data->described()) {
      // Read from a description, tiles not loaded: say what it said.
      ts["holes"] = d->holes;
      ts["paint"] = d->paint;
      ts["content_hash"] = toHex(d->contentHash);
    } else {
      std::vector<bool> present(static_cast<size_t>(tiles));
      for (int i = 0; i < tiles; ++i) present[size_t(i)] = t.data->tileHash(terrain::TileKind::Holes, 0, i) != 0;
      ts["holes"] = tileBitmap(present);
      Json paint = Json::array();
      for (int l = 0; l < tr.paint.layerCount(); ++l) {
        for (int i = 0; i < tiles; ++i) present[size_t(i)] = t.data->tileHash(terrain::TileKind::Paint, l, i) != 0;
        paint.push_back(tileBitmap(present));
      }
      ts["paint"] = std::move(paint);
      ts["content_hash"] = toHex(t.data->contentHash());
    }
    o["tiles"] = std::move(ts);
    out.push_back(std::move(o));
  }
  return out;
}

bool readTerrains(JsonReader& r, const Json& json, const std::string& path, SceneState& state) {
  if (!r.array(json, path)) return false;
  for (size_t i = 0; i < json.size(); ++i)
    if (!readTerrain(r, json[i], jsonIndex(path, i), state)) return false;
  return true;
}

}  // namespace hs::scene
