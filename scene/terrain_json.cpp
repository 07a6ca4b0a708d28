#include "scene/terrain_json.h"

#include <cmath>

#include <QByteArray>

#include "core/content_hash.h"
#include "scene/json_path_reader.h"

namespace hs::scene {
namespace {

QJsonArray vec2Json(const glm::dvec2& v) { return {v.x, v.y}; }
QJsonArray vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

QJsonObject materialJson(const terrain::Material& m) {
  QJsonObject o;
  o["name"] = QString::fromStdString(m.name);
  o["albedo"] = QJsonArray{double(m.albedo.x), double(m.albedo.y), double(m.albedo.z)};
  o["albedo_texture"] = QString::fromStdString(m.albedoTexture);
  o["normal_texture"] = QString::fromStdString(m.normalTexture);
  o["roughness"] = double(m.roughness);
  o["tiling_m"] = double(m.tilingMetres);
  return o;
}

QJsonObject ruleJson(const terrain::PaintRule& r) {
  QJsonObject o;
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

struct Reader : JsonPathReader {
  bool vec(const QJsonValue& v, const std::string& path, double* out, int n) { return numbers(v, path, out, n); }
  bool material(const QJsonValue& v, const std::string& path, terrain::Material& m) {
    if (!v.isObject()) return fail(path, "expected a material object");
    const QJsonObject o = v.toObject();
    m.name = o["name"].toString().toStdString();
    double c[3], rough, tiling;
    if (!vec(o["albedo"], path + ".albedo", c, 3) || !number(o["roughness"], path + ".roughness", rough) ||
        !number(o["tiling_m"], path + ".tiling_m", tiling))
      return false;
    if (!(tiling > 0.0)) return fail(path + ".tiling_m", "must be positive");
    m.albedo = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
    m.albedoTexture = o["albedo_texture"].toString().toStdString();
    m.normalTexture = o["normal_texture"].toString().toStdString();
    m.roughness = float(std::clamp(rough, 0.0, 1.0));
    m.tilingMetres = float(tiling);
    return true;
  }
  bool rule(const QJsonValue& v, const std::string& path, terrain::PaintRule& r, int layers) {
    if (!v.isObject()) return fail(path, "expected a paint rule object");
    const QJsonObject o = v.toObject();
    double layer, strength;
    if (!number(o["layer"], path + ".layer", layer) || !number(o["strength"], path + ".strength", strength))
      return false;
    if (layer < 0 || layer >= layers || layer != std::floor(layer))
      return fail(path + ".layer", "not a layer of this terrain (0.." + std::to_string(layers - 1) + ")");
    r.layer = int(layer);
    r.strength = float(strength);
    r.enabled = o["enabled"].toBool(true);
    r.useAltitude = o["use_altitude"].toBool(false);
    r.useSlope = o["use_slope"].toBool(false);
    for (auto [key, dst] : {std::pair{"altitude_min", &r.altitudeMin}, {"altitude_max", &r.altitudeMax},
                            {"altitude_blend", &r.altitudeBlend}, {"slope_min", &r.slopeMin},
                            {"slope_max", &r.slopeMax}, {"slope_blend", &r.slopeBlend}})
      if (!number(o[key], path + "." + key, *dst)) return false;
    return true;
  }
};

}  // namespace

QJsonArray paintRulesToJson(const std::vector<terrain::PaintRule>& rules) {
  QJsonArray a;
  for (const auto& r : rules) a.append(ruleJson(r));
  return a;
}

bool paintRulesFromJson(const QJsonArray& json, int layers, std::vector<terrain::PaintRule>& out, std::string& error) {
  Reader r{{error}};
  out.clear();
  for (int k = 0; k < json.size(); ++k) {
    terrain::PaintRule rule;
    if (!r.rule(json[k], "[" + std::to_string(k) + "]", rule, layers)) return false;
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

QJsonArray terrainsToJson(const SceneState& state) {
  QJsonArray out;
  for (const auto& [id, t] : state.terrains) {
    if (!t.data) continue;
    const terrain::Terrain& tr = t.data->terrain();
    const terrain::Heightfield& hf = tr.height;
    QJsonObject o;
    o["id"] = double(id);
    o["name"] = QString::fromStdString(t.name);
    o["samples"] = QJsonArray{hf.samplesX(), hf.samplesY()};
    o["spacing_m"] = vec2Json(hf.spacing());
    o["size_m"] = vec2Json(hf.sizeMetres());
    o["origin"] = vec3Json(hf.origin());
    if (hf.geo().valid()) {
      QJsonObject crs;
      crs["wkt"] = QString::fromStdString(hf.geo().crsWkt);
      crs["name"] = QString::fromStdString(hf.geo().crsName);
      crs["epsg"] = hf.geo().epsg;
      o["crs"] = crs;
    }
    o["layers"] = tr.paint.layerCount();
    QJsonArray materials;
    for (const auto& m : t.materials) materials.append(materialJson(m));
    o["materials"] = materials;
    o["paint_rules"] = paintRulesToJson(t.paintRules);
    // Tile summary: which sparse tiles hold data, and the content of all.
    const int tiles = hf.heights().tileCount();
    QJsonObject ts;
    ts["tile_size"] = terrain::kTileSize;
    ts["tiles"] = QJsonArray{hf.heights().tilesX(), hf.heights().tilesY()};
    if (const auto& d = t.data->described()) {
      // Read from a description, tiles not loaded: say what it said.
      ts["holes"] = QString::fromStdString(d->holes);
      QJsonArray paint;
      for (const auto& p : d->paint) paint.append(QString::fromStdString(p));
      ts["paint"] = paint;
      ts["content_hash"] = QString::fromStdString(toHex(d->contentHash));
    } else {
      std::vector<bool> present(static_cast<size_t>(tiles));
      for (int i = 0; i < tiles; ++i) present[size_t(i)] = t.data->tileHash(terrain::TileKind::Holes, 0, i) != 0;
      ts["holes"] = QString::fromStdString(tileBitmap(present));
      QJsonArray paint;
      for (int l = 0; l < tr.paint.layerCount(); ++l) {
        for (int i = 0; i < tiles; ++i) present[size_t(i)] = t.data->tileHash(terrain::TileKind::Paint, l, i) != 0;
        paint.append(QString::fromStdString(tileBitmap(present)));
      }
      ts["paint"] = paint;
      ts["content_hash"] = QString::fromStdString(toHex(t.data->contentHash()));
    }
    o["tiles"] = ts;
    out.append(o);
  }
  return out;
}

bool terrainsFromJson(const QJsonArray& json, SceneState& state, std::string& error) {
  Reader r{{error}};
  for (int i = 0; i < json.size(); ++i) {
    const std::string p = "terrains[" + std::to_string(i) + "]";
    const QJsonObject o = json[i].toObject();
    double id = 0, samples[2], spacing[2], origin[3], layers = 0;
    if (!r.number(o["id"], p + ".id", id) || !r.vec(o["samples"], p + ".samples", samples, 2) ||
        !r.vec(o["spacing_m"], p + ".spacing_m", spacing, 2) || !r.vec(o["origin"], p + ".origin", origin, 3) ||
        !r.number(o["layers"], p + ".layers", layers))
      return false;
    if (id < 1 || id != std::floor(id)) return r.fail(p + ".id", "expected a terrain id (whole number >= 1)");
    if (!(spacing[0] > 0.0 && spacing[1] > 0.0)) return r.fail(p + ".spacing_m", "must be positive");
    if (layers < 1 || layers > terrain::kMaxPaintLayers || layers != std::floor(layers))
      return r.fail(p + ".layers", "expected 1.." + std::to_string(terrain::kMaxPaintLayers));
    TerrainAsset t;
    t.id = TerrainId(id);
    t.name = o["name"].toString().toStdString();
    const QJsonArray materials = o["materials"].toArray();
    if (materials.size() != int(layers)) return r.fail(p + ".materials", "expected one material per layer");
    for (int m = 0; m < materials.size(); ++m) {
      terrain::Material mat;
      if (!r.material(materials[m], p + ".materials[" + std::to_string(m) + "]", mat)) return false;
      t.materials.push_back(mat);
    }
    std::string ruleError;
    if (!paintRulesFromJson(o["paint_rules"].toArray(), int(layers), t.paintRules, ruleError))
      return r.fail(p + ".paint_rules" + ruleError.substr(0, ruleError.find(':')), ruleError.substr(ruleError.find(':') + 2));
    terrain::HeightfieldDesc d;
    if (samples[0] != std::floor(samples[0]) || samples[1] != std::floor(samples[1]))
      return r.fail(p + ".samples", "expected whole numbers");
    d.samplesX = int(std::clamp(samples[0], 0.0, 1e6));
    d.samplesY = int(std::clamp(samples[1], 0.0, 1e6));
    d.sizeMetres = glm::dvec2(spacing[0], spacing[1]) * glm::dvec2(d.samplesX - 1, d.samplesY - 1);
    d.origin = glm::dvec3(origin[0], origin[1], origin[2]);
    if (o.contains("crs")) {
      const QJsonObject crs = o["crs"].toObject();
      d.geo.crsWkt = crs["wkt"].toString().toStdString();
      d.geo.crsName = crs["name"].toString().toStdString();
      d.geo.epsg = crs["epsg"].toInt();
    }
    auto made = terrain::Terrain::create(d, t.materials);
    if (!made) return r.fail(p, made.error());
    made->height.setSpacing(glm::dvec2(spacing[0], spacing[1]));
    t.data = std::make_shared<TerrainData>(made.take());
    const QJsonObject ts = o["tiles"].toObject();
    TerrainData::DescribedTiles described;
    bool ok = false;
    described.contentHash = ts["content_hash"].toString().toULongLong(&ok, 16);
    if (!ok) return r.fail(p + ".tiles.content_hash", "expected a hexadecimal content hash");
    described.holes = ts["holes"].toString().toStdString();
    for (const QJsonValue& v : ts["paint"].toArray()) described.paint.push_back(v.toString().toStdString());
    if (int(described.paint.size()) != int(layers)) return r.fail(p + ".tiles.paint", "expected one entry per layer");
    t.data->setDescribed(std::move(described));
    if (!state.terrains.emplace(t.id, std::move(t)).second) return r.fail(p + ".id", "duplicate terrain id");
  }
  return true;
}

}  // namespace hs::scene
