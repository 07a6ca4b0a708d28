#include "scene/scene_json.h"

#include <cmath>

#include <QJsonArray>
#include <QJsonDocument>

#include "core/content_hash.h"
#include "scene/fields.h"
#include "scene/json_path_reader.h"
#include "scene/terrain_json.h"
#include "sequencer/sequence_json.h"

namespace hs::scene {
namespace {

QJsonArray vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }


template <class Target>
QJsonValue fieldToJson(const FieldInfo<Target>& f, const Target& t) {
  const FieldValue v = f.get(t);
  switch (f.type) {
    case FieldType::Double: return std::get<double>(v);
    case FieldType::Bool: return std::get<bool>(v);
    case FieldType::Enum: {
      const int64_t i = std::get<int64_t>(v);
      return i >= 0 && size_t(i) < f.enumNames.size() ? QJsonValue(QString::fromStdString(f.enumNames[size_t(i)]))
                                                     : QJsonValue(double(i));
    }
    case FieldType::Vec3:
    case FieldType::Color: return vec3Json(std::get<glm::dvec3>(v));
    case FieldType::String: return QString::fromStdString(std::get<std::string>(v));
    case FieldType::AssetRef: return double(std::get<int64_t>(v));
  }
  return {};
}

// Reading: each helper names the JSON path of what it could not read.
struct Reader : JsonPathReader {
  bool id(const QJsonValue& v, const std::string& path, uint64_t& out) {
    double d = 0.0;
    if (!number(v, path, d)) return false;
    if (d < 0 || d != std::floor(d) || d > 9007199254740992.0) return fail(path, "expected an id (whole number >= 0)");
    out = uint64_t(d);
    return true;
  }
  bool vec3(const QJsonValue& v, const std::string& path, glm::dvec3& out) {
    return numbers(v, path, &out[0], 3, "[x, y, z]");
  }
  template <class Target>
  bool field(const FieldInfo<Target>& f, const QJsonValue& v, const std::string& path, Target& t) {
    FieldValue value;
    switch (f.type) {
      case FieldType::Double: {
        double d;
        if (!number(v, path, d)) return false;
        value = d;
        break;
      }
      case FieldType::Bool:
        if (!v.isBool()) return fail(path, "expected true or false");
        value = v.toBool();
        break;
      case FieldType::Enum: {
        const std::string name = v.toString().toStdString();
        int64_t index = -1;
        for (size_t i = 0; i < f.enumNames.size(); ++i)
          if (f.enumNames[i] == name) index = int64_t(i);
        if (index < 0) return fail(path, "unknown value '" + name + "'");
        value = index;
        break;
      }
      case FieldType::Vec3:
      case FieldType::Color: {
        glm::dvec3 x;
        if (!vec3(v, path, x)) return false;
        value = x;
        break;
      }
      case FieldType::String:
        if (!v.isString()) return fail(path, "expected a string");
        value = v.toString().toStdString();
        break;
      case FieldType::AssetRef: {
        uint64_t a;
        if (!id(v, path, a)) return false;
        value = int64_t(a);
        break;
      }
    }
    f.set(t, value);
    return true;
  }
};

}  // namespace

QJsonObject sceneToJson(const SceneState& state) {
  QJsonObject root;
  root["format"] = "hybridscape-scene";
  root["version"] = kSceneFormatVersion;

  QJsonObject settings;
  for (const auto& f : settingsFields()) settings[QString::fromStdString(f.key)] = fieldToJson(f, state.settings);
  root["settings"] = settings;

  QJsonArray roots;
  for (EntityId id : state.roots) roots.append(double(id));
  root["roots"] = roots;

  QJsonArray entities;
  for (const auto& [id, e] : state.entities) {
    QJsonObject o;
    o["id"] = double(id);
    o["name"] = QString::fromStdString(e.name);
    o["parent"] = double(e.parent);
    QJsonArray children;
    for (EntityId c : e.children) children.append(double(c));
    o["children"] = children;
    o["visible"] = e.visible;
    QJsonObject t;
    t["translation"] = vec3Json(e.transform.translation);
    // The quaternion itself, not Euler angles: saving must not change a value.
    const auto& q = e.transform.rotation;
    t["rotation"] = QJsonArray{q.w, q.x, q.y, q.z};
    t["scale"] = vec3Json(e.transform.scale);
    o["transform"] = t;
    QJsonObject components;
    for (const auto& c : entityComponents()) {
      if (!c.optional || !c.has(e)) continue;
      QJsonObject co;
      for (const auto& f : c.fields)
        if (f.serialized) co[QString::fromStdString(f.key)] = fieldToJson(f, e);
      // A reference, not a field (fields.cpp says why).
      if (c.key == "terrain") co["terrain_id"] = double(e.terrain->terrain);
      components[QString::fromStdString(c.key)] = co;
    }
    o["components"] = components;
    entities.append(o);
  }
  root["entities"] = entities;

  QJsonArray assets;
  for (const auto& [id, a] : state.assets) {
    QJsonObject o;
    o["id"] = double(id);
    o["name"] = QString::fromStdString(a.name);
    o["source"] = QString::fromStdString(a.sourcePath);
    o["hash"] = QString::fromStdString(toHex(a.contentHash));
    if (!a.importReportJson.empty())
      o["import_report"] = QJsonDocument::fromJson(QByteArray::fromStdString(a.importReportJson)).object();
    // Coarser levels: their blobs are "mesh/<id>/lod<level>" (hscene_file.cpp).
    if (!a.lods.empty()) {
      QJsonArray lods;
      for (size_t k = 0; k < a.lods.size(); ++k) {
        const MeshLod& l = a.lods[k];
        QJsonObject lo;
        lo["level"] = double(k + 1);
        lo["hash"] = QString::fromStdString(toHex(l.contentHash));
        lo["triangles"] = double(l.triangles);
        lo["hausdorff_m"] = l.hausdorff;
        lods.append(lo);
      }
      o["lods"] = lods;
    }
    if (!a.processReportJson.empty())
      o["process_report"] = QJsonDocument::fromJson(QByteArray::fromStdString(a.processReportJson)).object();
    assets.append(o);
  }
  root["assets"] = assets;
  root["terrains"] = terrainsToJson(state);
  // The timeline, in the sequencer's own JSON (it has no Qt), embedded as an object.
  root["sequence"] = QJsonDocument::fromJson(QByteArray::fromStdString(sequencer::sequenceToJsonText(state.sequence))).object();
  return root;
}

std::string canonicalJson(const SceneState& state) {
  return QJsonDocument(sceneToJson(state)).toJson(QJsonDocument::Compact).toStdString();
}

std::optional<SceneState> sceneFromJson(const QJsonObject& json, std::string& error) {
  Reader r{{error}};
  SceneState s;
  if (json["format"].toString() != "hybridscape-scene") {
    r.fail("format", "not a Hybridscape scene description");
    return std::nullopt;
  }
  const QJsonObject settings = json["settings"].toObject();
  for (const auto& f : settingsFields()) {
    const QJsonValue v = settings[QString::fromStdString(f.key)];
    if (v.isUndefined()) continue;  // older files: keep the default
    if (!r.field(f, v, "settings." + f.key, s.settings)) return std::nullopt;
  }

  const QJsonArray roots = json["roots"].toArray();
  for (int i = 0; i < roots.size(); ++i) {
    uint64_t id;
    if (!r.id(roots[i], "roots[" + std::to_string(i) + "]", id)) return std::nullopt;
    s.roots.push_back(id);
  }

  const QJsonArray entities = json["entities"].toArray();
  for (int i = 0; i < entities.size(); ++i) {
    const std::string p = "entities[" + std::to_string(i) + "]";
    const QJsonObject o = entities[i].toObject();
    Entity e;
    if (!r.id(o["id"], p + ".id", e.id) || !r.id(o["parent"], p + ".parent", e.parent))
      return std::nullopt;
    if (e.id == kNoEntity) {
      r.fail(p + ".id", "0 is not a valid entity id");
      return std::nullopt;
    }
    e.name = o["name"].toString().toStdString();
    e.visible = o["visible"].toBool(true);
    const QJsonArray children = o["children"].toArray();
    for (int c = 0; c < children.size(); ++c) {
      uint64_t cid;
      if (!r.id(children[c], p + ".children[" + std::to_string(c) + "]", cid)) return std::nullopt;
      e.children.push_back(cid);
    }
    const QJsonObject t = o["transform"].toObject();
    const QJsonArray q = t["rotation"].toArray();
    if (!r.vec3(t["translation"], p + ".transform.translation", e.transform.translation) ||
        !r.vec3(t["scale"], p + ".transform.scale", e.transform.scale))
      return std::nullopt;
    if (q.size() != 4) {
      r.fail(p + ".transform.rotation", "expected a quaternion [w, x, y, z]");
      return std::nullopt;
    }
    double qv[4];
    for (int k = 0; k < 4; ++k)
      if (!r.number(q[k], p + ".transform.rotation[" + std::to_string(k) + "]", qv[k])) return std::nullopt;
    e.transform.rotation = glm::dquat(qv[0], qv[1], qv[2], qv[3]);
    if (glm::length(e.transform.rotation) < 1e-12) {
      r.fail(p + ".transform.rotation", "zero quaternion");
      return std::nullopt;
    }

    const QJsonObject components = o["components"].toObject();
    for (auto it = components.begin(); it != components.end(); ++it) {
      const std::string key = it.key().toStdString();
      const ComponentInfo* c = findComponent(key);
      if (!c || !c->optional) {
        r.fail(p + ".components." + key, "unknown component");
        return std::nullopt;
      }
      c->add(e);
      const QJsonObject co = it.value().toObject();
      for (const auto& f : c->fields) {
        if (!f.serialized) continue;
        const QJsonValue v = co[QString::fromStdString(f.key)];
        if (v.isUndefined()) continue;
        if (!r.field(f, v, p + ".components." + key + "." + f.key, e)) return std::nullopt;
      }
      if (key == "terrain" && co.contains("terrain_id") &&
          !r.id(co["terrain_id"], p + ".components.terrain.terrain_id", e.terrain->terrain))
        return std::nullopt;
    }
    if (!s.entities.emplace(e.id, std::move(e)).second) {
      r.fail(p + ".id", "duplicate entity id");
      return std::nullopt;
    }
  }

  const QJsonArray assets = json["assets"].toArray();
  for (int i = 0; i < assets.size(); ++i) {
    const std::string p = "assets[" + std::to_string(i) + "]";
    const QJsonObject o = assets[i].toObject();
    MeshAsset a;
    if (!r.id(o["id"], p + ".id", a.id)) return std::nullopt;
    a.name = o["name"].toString().toStdString();
    a.sourcePath = o["source"].toString().toStdString();
    bool ok = false;
    a.contentHash = o["hash"].toString().toULongLong(&ok, 16);
    if (!ok) {
      r.fail(p + ".hash", "expected a hexadecimal content hash");
      return std::nullopt;
    }
    if (o.contains("import_report"))
      a.importReportJson =
          QJsonDocument(o["import_report"].toObject()).toJson(QJsonDocument::Compact).toStdString();
    // LOD levels (format 3): hash and error here, the data from their blobs.
    const QJsonArray lods = o["lods"].toArray();
    double previous = 0.0;
    for (int k = 0; k < lods.size(); ++k) {
      const std::string lp = p + ".lods[" + std::to_string(k) + "]";
      const QJsonObject lo = lods[k].toObject();
      MeshLod l;
      double level = 0;
      if (!r.number(lo["level"], lp + ".level", level)) return std::nullopt;
      if (level != double(k + 1)) {
        r.fail(lp + ".level", "expected level " + std::to_string(k + 1) + " (levels are numbered from 1 in order)");
        return std::nullopt;
      }
      l.contentHash = lo["hash"].toString().toULongLong(&ok, 16);
      if (!ok) {
        r.fail(lp + ".hash", "expected a hexadecimal content hash");
        return std::nullopt;
      }
      if (!r.number(lo["hausdorff_m"], lp + ".hausdorff_m", l.hausdorff)) return std::nullopt;
      double triangles = 0;
      if (!r.number(lo["triangles"], lp + ".triangles", triangles)) return std::nullopt;
      if (triangles < 0 || triangles != std::floor(triangles)) {
        r.fail(lp + ".triangles", "expected a whole number of triangles");
        return std::nullopt;
      }
      l.triangles = size_t(triangles);
      // The renderer's choice relies on errors growing along the chain.
      if (l.hausdorff < previous) {
        r.fail(lp + ".hausdorff_m", "smaller than the previous level's (errors must not decrease)");
        return std::nullopt;
      }
      previous = l.hausdorff;
      a.lods.push_back(std::move(l));
    }
    if (o.contains("process_report"))
      a.processReportJson =
          QJsonDocument(o["process_report"].toObject()).toJson(QJsonDocument::Compact).toStdString();
    if (!s.assets.emplace(a.id, std::move(a)).second) {
      r.fail(p + ".id", "duplicate asset id");
      return std::nullopt;
    }
  }

  if (json.contains("terrains") && !terrainsFromJson(json["terrains"].toArray(), s, error)) return std::nullopt;

  if (json.contains("sequence")) {
    const QByteArray text = QJsonDocument(json["sequence"].toObject()).toJson(QJsonDocument::Compact);
    std::string seqError;
    auto seq = sequencer::sequenceFromJsonText(std::string_view(text.constData(), size_t(text.size())), seqError);
    if (!seq) {
      r.fail("sequence", seqError);
      return std::nullopt;
    }
    s.sequence = std::move(*seq);
  }

  if (const std::string problem = s.validate(); !problem.empty()) {
    error = "inconsistent hierarchy: " + problem;
    return std::nullopt;
  }
  return s;
}

}  // namespace hs::scene
