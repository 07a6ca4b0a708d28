#include "scene/scene_json.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <type_traits>

#include "core/content_hash.h"
#include "particles/emitter.h"
#include "scene/asset_reports.h"
#include "scene/emitter_tracks.h"
#include "scene/camera_post.h"
#include "scene/fields.h"
#include "scene/key_value_ranges.h"
#include "scene/light_units.h"
#include "scene/ocio_config.h"
#include "scene/object_tracks.h"
#include "scene/foliage_file.h"
#include "scene/terrain_json.h"
#include "sequencer/sequence_json.h"

namespace hs::scene {
namespace {

// Ids are whole numbers a double holds exactly, so other JSON tools (which
// read numbers as doubles) see the same ids.
constexpr int64_t kMaxId = int64_t(1) << 53;

Json vec3Json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

template <class Target>
Json fieldToJson(const FieldInfo<Target>& f, const Target& t) {
  const FieldValue v = f.get(t);
  switch (f.type) {
    case FieldType::Double: return std::get<double>(v);
    case FieldType::Bool: return std::get<bool>(v);
    case FieldType::Enum: {
      const int64_t i = std::get<int64_t>(v);
      return i >= 0 && size_t(i) < f.enumNames.size() ? Json(f.enumNames[size_t(i)]) : Json(i);
    }
    case FieldType::Vec3:
    case FieldType::Color: return vec3Json(std::get<glm::dvec3>(v));
    case FieldType::String: return std::get<std::string>(v);
    case FieldType::AssetRef: return std::get<int64_t>(v);
  }
  return nullptr;
}

Json entityToJson(const Entity& e) {
  Json o = Json::object();
  o["id"] = e.id;
  o["name"] = e.name;
  o["parent"] = e.parent;
  o["children"] = e.children;
  o["visible"] = e.visible;
  Json t = Json::object();
  t["translation"] = vec3Json(e.transform.translation);
  // The quaternion itself, not Euler angles: saving must not change a value.
  const auto& q = e.transform.rotation;
  t["rotation"] = Json::array({q.w, q.x, q.y, q.z});
  t["scale"] = vec3Json(e.transform.scale);
  o["transform"] = std::move(t);
  Json components = Json::object();
  for (const auto& c : entityComponents()) {
    if (!c.optional || !c.has(e)) continue;
    Json co = Json::object();
    for (const auto& f : c.fields)
      if (f.serialized) co[f.key] = fieldToJson(f, e);
    // A reference, not a field (fields.cpp says why).
    if (c.key == "terrain") co["terrain_id"] = e.terrain->terrain;
    // The scene settings this camera overrides (camera_post.h), when any.
    if (c.key == "camera" && !e.camera->post.empty()) {
      Json post = Json::object();
      for (const auto& [key, value] : e.camera->post)
        if (const EntityField* f = findCameraPostField(key)) post[key] = fieldToJson(*f, e);
      co["post"] = std::move(post);
    }
    // An emitter is its own declared table (particles/emitter.h, fields.cpp says why).
    if (c.key == "particles") co = particles::emitterToJson(e.particles->desc);
    components[c.key] = std::move(co);
  }
  o["components"] = std::move(components);
  return o;
}

Json assetToJson(const MeshAsset& a) {
  Json o = Json::object();
  o["id"] = a.id;
  o["name"] = a.name;
  o["source"] = a.sourcePath;
  o["hash"] = toHex(a.contentHash);
  if (!a.importReport.is_null()) o["import_report"] = a.importReport;
  // Coarser levels: their blobs are "mesh/<id>/lod<level>" (hscene_file.cpp).
  if (!a.lods.empty()) {
    Json lods = Json::array();
    for (size_t k = 0; k < a.lods.size(); ++k) {
      const MeshLod& l = a.lods[k];
      Json lo = Json::object();
      lo["level"] = k + 1;
      lo["hash"] = toHex(l.contentHash);
      lo["triangles"] = l.triangles;
      lo["hausdorff_m"] = l.hausdorff;
      lods.push_back(std::move(lo));
    }
    o["lods"] = std::move(lods);
  }
  if (!a.processReport.is_null()) o["process_report"] = a.processReport;
  // Format 5: the document material of each slot (mesh_materials.h).
  if (!a.materialSlots.empty()) o["material_slots"] = a.materialSlots;
  // Format 12: the stored impostor's hash; its images are the blob
  // "mesh/<id>/impostor" (foliage/impostor_images.h).
  if (a.impostorHash != 0) o["impostor_hash"] = toHex(a.impostorHash);
  // Format 16: the cluster hierarchy's index blob "clusters/<hash>" (cluster_file.h).
  if (a.clustersHash != 0) o["clusters_hash"] = toHex(a.clustersHash);
  return o;
}

Json materialToJson(const Material& m) {
  Json o = Json::object();
  o["id"] = m.id;
  o["name"] = m.name;
  o["asset"] = m.asset;
  for (const auto& f : materialFields())
    if (f.serialized) o[f.key] = fieldToJson(f, m);
  return o;
}

// A mesh's texture names its place in the mesh blob; a standalone one its
// own blob ("texture/<id>", texture_blob.h) by hash.
Json textureToJson(const TextureAsset& t) {
  Json o = Json::object();
  o["id"] = t.id;
  o["name"] = t.name;
  if (t.standalone()) {
    o["hash"] = toHex(t.contentHash);
    o["srgb"] = t.srgb;
  } else {
    o["asset"] = t.asset;
    o["mesh_texture"] = t.meshTexture;
  }
  return o;
}

// Reading: each helper names the JSON path of what it could not read.
// Members a file written by an older build may lack are optional and keep
// their defaults; what every build wrote is required.
struct Reader : JsonReader {
  using JsonReader::JsonReader;
  std::vector<std::string>* warnings = nullptr;  // values clamped or repaired
  int formatVersion = kSceneFormatVersion;       // the description's "version" (keys added later are optional)

  // A loaded value that breaks its field's range or rule: clamped by the
  // setter, or repaired by the field, and named in a warning.
  template <class Target>
  void warnOutOfRange(const std::string& who, const std::string& fieldPath, const FieldInfo<Target>& f,
                      const FieldValue& v, const std::string& problem, const Target& now) {
    const auto shown = [&f](const FieldValue& x) {
      const std::string text = formatFieldValue(f.type, x, f.enumNames, 6);
      return f.type == FieldType::String ? "'" + text + "'" : text;
    };
    if (warnings) warnings->push_back(who + fieldPath + " " + shown(v) + " " + problem + "; now " + shown(f.get(now)));
  }
  static std::string entityLabel(const Entity& e) {
    return "entity " + std::to_string(e.id) + " '" + e.name + "': ";
  }

  bool id(const Json* v, const std::string& path, uint64_t& out) {
    if (!v) return fail(path, "missing");
    int64_t i = 0;
    if (!integer(*v, path, i, 0, kMaxId)) return false;
    out = uint64_t(i);
    return true;
  }
  bool vec3(const Json* v, const std::string& path, glm::dvec3& out) {
    if (!v) return fail(path, "missing");
    return numbers(*v, path, &out[0], 3, "[x, y, z]");
  }
  bool hash(const Json* v, const std::string& path, uint64_t& out) {
    std::string text;
    if (!v) return fail(path, "missing");
    if (!string(*v, path, text)) return false;
    return fromHex(text, out) || fail(path, "expected a hexadecimal content hash, not '" + text + "'");
  }
  // An optional array member: absent (or null) is empty.
  const Json* optArray(const Json& obj, const std::string& path, std::string_view key) {
    const Json* m = member(obj, key);
    if (!m || m->is_null()) return nullptr;
    return array(*m, jsonPath(path, key)) ? m : nullptr;
  }
  template <class Target>
  bool field(const FieldInfo<Target>& f, const Json& v, const std::string& path, Target& t) {
    FieldValue value;
    switch (f.type) {
      case FieldType::Double: {
        double d;
        if (!number(v, path, d)) return false;
        value = d;
        break;
      }
      case FieldType::Bool: {
        bool b;
        if (!boolean(v, path, b)) return false;
        value = b;
        break;
      }
      case FieldType::Enum: {
        std::string name;
        if (!string(v, path, name)) return false;
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
        if (!vec3(&v, path, x)) return false;
        value = x;
        break;
      }
      case FieldType::String: {
        std::string s;
        if (!string(v, path, s)) return false;
        value = std::move(s);
        break;
      }
      case FieldType::AssetRef: {
        uint64_t a;
        if (!id(&v, path, a)) return false;
        value = int64_t(a);
        break;
      }
    }
    f.set(t, value);
    // Only what the value alone decides here; rules between fields once the
    // whole entity is read (checkEntity).
    if (const std::string problem = fieldValueProblem(f, value, static_cast<const Target*>(nullptr));
        !problem.empty()) {
      if (f.repair && !fieldValueProblem(f, f.get(t), static_cast<const Target*>(nullptr)).empty()) f.repair(t);
      if constexpr (std::is_same_v<Target, Entity>) {
        // "entities[1].components.camera.fov_deg" -> "camera.fov_deg"
        const size_t at = path.rfind("components.");
        warnOutOfRange(entityLabel(t), at == std::string::npos ? path : path.substr(at + 11), f, value, problem, t);
      } else {
        warnOutOfRange(std::string(), path, f, value, problem, t);
      }
    }
    return true;
  }

  // A camera's "post" object: each member a setting it overrides, read
  // and checked as that field; a key this build does not know (a newer
  // build's setting) is dropped with a warning.
  bool cameraPost(const Json& co, const std::string& p, Entity& e) {
    const Json* post = member(co, "post");
    if (!post) return true;
    const std::string path = jsonPath(p, "post");
    if (!object(*post, path)) return false;
    for (auto it = post->begin(); it != post->end(); ++it) {
      const EntityField* f = findCameraPostField(it.key());
      if (!f) {
        if (warnings)
          warnings->push_back(entityLabel(e) + "camera.post." + it.key() +
                              ": no such post setting a camera overrides; dropped");
        continue;
      }
      if (!field(*f, it.value(), jsonPath(path, it.key()), e)) return false;
    }
    return true;
  }

  // The rules between an entity's fields (the clip planes) and its name,
  // which is read apart from the fields.
  void checkEntity(Entity& e) {
    for (const auto& c : entityComponents()) {
      if (!c.has(e)) continue;
      for (const auto& f : c.fields) {
        if (!f.serialized || !f.check) continue;
        const FieldValue v = f.get(e);
        const std::string problem = fieldValueProblem(f, v, &e);
        if (problem.empty()) continue;
        const std::string who = entityLabel(e);
        if (f.repair) f.repair(e);
        else f.set(e, v);  // the setter's own clamp (a zero scale becomes a tiny one)
        warnOutOfRange(who, c.key + "." + f.key, f, v, problem, e);
      }
    }
  }

  bool transform(const Json* v, const std::string& path, Transform& t) {
    if (!v) return fail(path, "missing");
    if (!object(*v, path) || !vec3(member(*v, "translation"), jsonPath(path, "translation"), t.translation) ||
        !vec3(member(*v, "scale"), jsonPath(path, "scale"), t.scale))
      return false;
    const std::string rp = jsonPath(path, "rotation");
    const Json* q = required(*v, path, "rotation");
    double qv[4];
    if (!q || !numbers(*q, rp, qv, 4, "a quaternion [w, x, y, z]")) return false;
    t.rotation = glm::dquat(qv[0], qv[1], qv[2], qv[3]);
    return glm::length(t.rotation) >= 1e-12 || fail(rp, "zero quaternion");
  }

  bool components(const Json& o, const std::string& path, Entity& e) {
    const Json* cs = member(o, "components");
    if (!cs) return true;
    const std::string cp = jsonPath(path, "components");
    if (!object(*cs, cp)) return false;
    for (const auto& [key, co] : cs->items()) {
      const std::string p = jsonPath(cp, key);
      const ComponentInfo* c = findComponent(key);
      if (!c || !c->optional) return fail(p, "unknown component");
      if (!object(co, p)) return false;
      c->add(e);
      if (key == "particles") {
        // Strict, as a hand-written emitter is: a damaged one refuses the
        // file with its path (particles/emitter.h names emitter and field).
        std::string error;
        std::optional<particles::EmitterDesc> d = particles::emitterFromJson(co, error, formatVersion);
        if (!d) return fail(p, error);
        e.particles->desc = std::move(*d);
        continue;
      }
      for (const auto& f : c->fields) {
        if (!f.serialized) continue;
        const Json* v = member(co, f.key);
        if (v && !field(f, *v, jsonPath(p, f.key), e)) return false;
      }
      if (key == "camera" && !cameraPost(co, p, e)) return false;
      if (key == "terrain" && member(co, "terrain_id") &&
          !id(member(co, "terrain_id"), jsonPath(p, "terrain_id"), e.terrain->terrain))
        return false;
    }
    return true;
  }

  bool entity(const Json& o, const std::string& p, Entity& e) {
    if (!object(o, p) || !id(member(o, "id"), jsonPath(p, "id"), e.id) ||
        !id(member(o, "parent"), jsonPath(p, "parent"), e.parent))
      return false;
    if (e.id == kNoEntity) return fail(jsonPath(p, "id"), "0 is not a valid entity id");
    if (!optString(o, p, "name", e.name) || !optBoolean(o, p, "visible", e.visible)) return false;
    if (const Json* children = optArray(o, p, "children")) {
      for (size_t c = 0; c < children->size(); ++c) {
        uint64_t cid;
        if (!id(&(*children)[c], jsonIndex(jsonPath(p, "children"), c), cid)) return false;
        e.children.push_back(cid);
      }
    }
    if (failed()) return false;
    if (!transform(member(o, "transform"), jsonPath(p, "transform"), e.transform) || !components(o, p, e))
      return false;
    checkEntity(e);
    return true;
  }

  // A report stored with an asset (asset_reports.h), read through its
  // reader and kept as its writer writes it: a file from an older build
  // comes back in the current form ("skipped_lines" becomes
  // "skipped_primitives"), and a bad member is refused with its path.
  template <class Report>
  bool report(const Json& o, const std::string& path, std::string_view key, Json& out) {
    const Json* m = member(o, key);
    if (!m || m->is_null()) return true;
    Report r;
    if (!fromJson(*this, *m, jsonPath(path, key), r)) return false;
    out = toJson(r);
    return true;
  }

  bool asset(const Json& o, const std::string& p, MeshAsset& a) {
    if (!object(o, p) || !id(member(o, "id"), jsonPath(p, "id"), a.id) || !optString(o, p, "name", a.name) ||
        !optString(o, p, "source", a.sourcePath) || !hash(member(o, "hash"), jsonPath(p, "hash"), a.contentHash) ||
        !report<AssetImportReport>(o, p, "import_report", a.importReport))
      return false;
    // LOD levels (format 3): hash and error here, the data from their blobs.
    const Json* lods = optArray(o, p, "lods");
    if (failed()) return false;
    double previous = 0.0;
    for (size_t k = 0; lods && k < lods->size(); ++k) {
      const std::string lp = jsonIndex(jsonPath(p, "lods"), k);
      const Json& lo = (*lods)[k];
      MeshLod l;
      int64_t level = 0, triangles = 0;
      if (!object(lo, lp)) return false;
      const Json* lv = required(lo, lp, "level");
      if (!lv || !integer(*lv, jsonPath(lp, "level"), level, 1, kMaxId)) return false;
      if (level != int64_t(k + 1))
        return fail(jsonPath(lp, "level"),
                    "expected level " + std::to_string(k + 1) + " (levels are numbered from 1 in order)");
      if (!hash(member(lo, "hash"), jsonPath(lp, "hash"), l.contentHash)) return false;
      const Json* h = required(lo, lp, "hausdorff_m");
      if (!h || !number(*h, jsonPath(lp, "hausdorff_m"), l.hausdorff)) return false;
      const Json* t = required(lo, lp, "triangles");
      if (!t || !integer(*t, jsonPath(lp, "triangles"), triangles, 0, kMaxId)) return false;
      l.triangles = size_t(triangles);
      // The renderer's choice relies on errors growing along the chain.
      if (l.hausdorff < previous)
        return fail(jsonPath(lp, "hausdorff_m"), "smaller than the previous level's (errors must not decrease)");
      previous = l.hausdorff;
      a.lods.push_back(std::move(l));
    }
    if (!report<AssetProcessReport>(o, p, "process_report", a.processReport)) return false;
    const Json* slots = optArray(o, p, "material_slots");
    for (size_t k = 0; slots && k < slots->size(); ++k) {
      uint64_t m;
      if (!id(&(*slots)[k], jsonIndex(jsonPath(p, "material_slots"), k), m)) return false;
      a.materialSlots.push_back(m);
    }
    if (const Json* ih = member(o, "impostor_hash"); ih && !hash(ih, jsonPath(p, "impostor_hash"), a.impostorHash))
      return false;
    if (const Json* ch = member(o, "clusters_hash"); ch && !hash(ch, jsonPath(p, "clusters_hash"), a.clustersHash))
      return false;
    return !failed();
  }

  bool material(const Json& o, const std::string& p, Material& m) {
    if (!object(o, p) || !id(member(o, "id"), jsonPath(p, "id"), m.id)) return false;
    if (m.id == kNoMaterial) return fail(jsonPath(p, "id"), "0 is not a valid material id");
    if (!optString(o, p, "name", m.name)) return false;
    if (member(o, "asset") && !id(member(o, "asset"), jsonPath(p, "asset"), m.asset)) return false;
    // Values out of their declared range are clamped by the declaration.
    for (const auto& f : materialFields()) {
      if (!f.serialized) continue;
      const Json* v = member(o, f.key);
      if (v && !field(f, *v, jsonPath(p, f.key), m)) return false;
    }
    return true;
  }

  bool texture(const Json& o, const std::string& p, TextureAsset& t) {
    if (!object(o, p) || !id(member(o, "id"), jsonPath(p, "id"), t.id)) return false;
    if (t.id == kNoTexture) return fail(jsonPath(p, "id"), "0 is not a valid texture id");
    if (!optString(o, p, "name", t.name)) return false;
    if (member(o, "asset")) {
      int64_t index = 0;
      const Json* mt = required(o, p, "mesh_texture");
      if (!id(member(o, "asset"), jsonPath(p, "asset"), t.asset) || !mt ||
          !integer(*mt, jsonPath(p, "mesh_texture"), index, 0, kMaxId))
        return false;
      t.meshTexture = int(std::min<int64_t>(index, INT32_MAX));
      return true;
    }
    return hash(member(o, "hash"), jsonPath(p, "hash"), t.contentHash) && optBoolean(o, p, "srgb", t.srgb);
  }
  // settings."post.lut": {"file", "hash"}; the bytes come from blob "lut/<hash>".
  bool lut(const Json& o, const std::string& p, LutData& out) {
    if (!object(o, p) || !optString(o, p, "file", out.fileName)) return false;
    if (out.fileName.empty()) return fail(jsonPath(p, "file"), "missing: a LUT needs its file name");
    return hash(member(o, "hash"), jsonPath(p, "hash"), out.contentHash);
  }
  // settings."post.ocio_config": {"file", "hash", "files": [{"path", "hash"}]};
  // each file's bytes come from blob "ocio/<hash>".
  bool ocioConfig(const Json& o, const std::string& p, OcioConfigData& out) {
    if (!object(o, p) || !optString(o, p, "file", out.fileName)) return false;
    if (out.fileName.empty()) return fail(jsonPath(p, "file"), "missing: a config needs its file name");
    if (!hash(member(o, "hash"), jsonPath(p, "hash"), out.contentHash)) return false;
    const Json* files = optArray(o, p, "files");
    if (failed()) return false;
    if (!files || files->empty()) return fail(jsonPath(p, "files"), "missing: a config needs at least its own file");
    for (size_t i = 0; i < files->size(); ++i) {
      const std::string fp = jsonIndex(jsonPath(p, "files"), i);
      OcioFile f;
      if (!object((*files)[i], fp) || !optString((*files)[i], fp, "path", f.path) ||
          !hash(member((*files)[i], "hash"), jsonPath(fp, "hash"), f.contentHash))
        return false;
      if (!ocioBundlePathSafe(f.path))
        return fail(jsonPath(fp, "path"), "'" + f.path + "' is not a path inside the config's bundle");
      out.files.push_back(std::move(f));
    }
    if (out.files.front().path != kOcioConfigEntry)
      return fail(jsonPath(p, "files"), std::string("the first file must be the config, '") + kOcioConfigEntry + "'");
    if (ocioBundleHash(out.files) != out.contentHash)
      return fail(jsonPath(p, "hash"), "does not match the files listed (damaged description)");
    return true;
  }
};

// A bad value fails `r`; a description whose parts do not fit together
// sets `inconsistency`.
std::optional<SceneState> readScene(const Json& json, Reader& r, std::string& inconsistency) {
  SceneState s;
  if (!r.object(json, "")) return std::nullopt;
  const Json* format = JsonReader::member(json, "format");
  if (!format || *format != "hybridscape-scene") {
    r.fail("format", "not a Hybridscape scene description");
    return std::nullopt;
  }
  if (const Json* v = JsonReader::member(json, "version"); v && v->is_number())
    r.formatVersion = int(std::clamp(v->get<double>(), 0.0, 1e6));
  if (const Json* settings = JsonReader::member(json, "settings")) {
    if (!r.object(*settings, "settings")) return std::nullopt;
    for (const auto& f : settingsFields()) {
      const Json* v = JsonReader::member(*settings, f.key);
      if (!v) continue;  // older files: keep the default
      if (!r.field(f, *v, jsonPath("settings", f.key), s.settings)) return std::nullopt;
    }
    if (const Json* lut = JsonReader::member(*settings, "post.lut");
        lut && !lut->is_null() && !r.lut(*lut, jsonPath("settings", "post.lut"), s.settings.post.lut))
      return std::nullopt;
    if (const Json* ocio = JsonReader::member(*settings, "post.ocio_config");
        ocio && !ocio->is_null() &&
        !r.ocioConfig(*ocio, jsonPath("settings", "post.ocio_config"), s.settings.post.ocioConfig))
      return std::nullopt;
  }

  const Json* roots = r.optArray(json, "", "roots");
  for (size_t i = 0; roots && i < roots->size(); ++i) {
    uint64_t id;
    if (!r.id(&(*roots)[i], jsonIndex("roots", i), id)) return std::nullopt;
    s.roots.push_back(id);
  }
  if (r.failed()) return std::nullopt;

  if (const Json* entities = r.optArray(json, "", "entities")) {
    for (size_t i = 0; i < entities->size(); ++i) {
      const std::string p = jsonIndex("entities", i);
      Entity e;
      if (!r.entity((*entities)[i], p, e)) return std::nullopt;
      if (!s.entities.emplace(e.id, std::move(e)).second) {
        r.fail(jsonPath(p, "id"), "duplicate entity id");
        return std::nullopt;
      }
    }
  }

  if (r.failed()) return std::nullopt;
  if (const Json* assets = r.optArray(json, "", "assets")) {
    for (size_t i = 0; i < assets->size(); ++i) {
      const std::string p = jsonIndex("assets", i);
      MeshAsset a;
      if (!r.asset((*assets)[i], p, a)) return std::nullopt;
      if (!s.assets.emplace(a.id, std::move(a)).second) {
        r.fail(jsonPath(p, "id"), "duplicate asset id");
        return std::nullopt;
      }
    }
  }

  if (r.failed()) return std::nullopt;
  if (const Json* materials = r.optArray(json, "", "materials")) {
    for (size_t i = 0; i < materials->size(); ++i) {
      const std::string p = jsonIndex("materials", i);
      Material m;
      if (!r.material((*materials)[i], p, m)) return std::nullopt;
      if (!s.materials.emplace(m.id, std::move(m)).second) {
        r.fail(jsonPath(p, "id"), "duplicate material id");
        return std::nullopt;
      }
    }
  }
  if (r.failed()) return std::nullopt;
  if (const Json* textures = r.optArray(json, "", "textures")) {
    for (size_t i = 0; i < textures->size(); ++i) {
      const std::string p = jsonIndex("textures", i);
      TextureAsset t;
      if (!r.texture((*textures)[i], p, t)) return std::nullopt;
      if (!s.textures.emplace(t.id, std::move(t)).second) {
        r.fail(jsonPath(p, "id"), "duplicate texture id");
        return std::nullopt;
      }
    }
  }
  if (r.failed()) return std::nullopt;
  if (const Json* terrains = r.optArray(json, "", "terrains"); terrains && !readTerrains(r, *terrains, "terrains", s))
    return std::nullopt;
  if (r.failed()) return std::nullopt;
  if (const Json* seq = JsonReader::member(json, "sequence");
      seq && !sequencer::readSequence(r, *seq, "sequence", s.sequence))
    return std::nullopt;
  if (r.failed()) return std::nullopt;
  if (const Json* f = JsonReader::member(json, "foliage"); f && !f->is_null()) {
    std::string e;
    if (!foliageFromJson(*f, s, e)) {
      // "foliage.cells[1].hash: expected 16 hex digits": its path and what.
      const size_t colon = e.find(": ");
      r.fail(colon == std::string::npos ? "foliage" : e.substr(0, colon),
             colon == std::string::npos ? e : e.substr(colon + 2));
      return std::nullopt;
    }
  }
  // Keyed values are held to their fields' ranges like the static ones.
  clampKeyValues(s, r.warnings);
  // Material and settings tracks: their targets and fields checked, keys clamped.
  checkObjectTracks(s, r.warnings);
  // Emitter spawn-value tracks: their keys and entities checked.
  checkEmitterTracks(s, r.warnings);

  // Before format 6 lights and exposure were in relative units; before
  // format 8 the exposure was relative to EV100 15.2 and the shaders folded
  // the BRDF's 1/π into the lights. A description without a version is
  // taken as this build's.
  const Json* versionJson = JsonReader::member(json, "version");
  const double version = versionJson && versionJson->is_number() ? versionJson->get<double>() : kSceneFormatVersion;
  if (version < kFirstPhysicalLightsFormat) {
    std::optional<double> oldExposure;
    if (const Json* settings = JsonReader::member(json, "settings")) {
      if (const Json* e = JsonReader::member(*settings, "exposure"); e && e->is_number())
        oldExposure = std::clamp(e->get<double>(), 0.001, 1000.0);  // the old field's range
    }
    migrateToPhysicalLightUnits(s, oldExposure);  // straight to this format's units
  } else if (version < kFirstPhysicalBrdfFormat) {
    // A file without exposure_ev100 meant its default, 15.2, which is this
    // build's default (the reference) once moved: it keeps the default.
    const Json* settings = JsonReader::member(json, "settings");
    const bool exposureStored = settings && JsonReader::member(*settings, "exposure_ev100");
    const float asRead = s.settings.exposureEv100;  // this build's default when not stored
    migrateToPhysicalBrdf(s);
    if (!exposureStored) s.settings.exposureEv100 = asRead;
  }
  // Before format 7 a sun's shadows followed settings.shadows alone.
  if (version < kFirstPerLightShadowsFormat) {
    for (auto& [id, e] : s.entities)
      if (e.light && e.light->type == Light::Type::Sun) e.light->castsShadows = true;
  }

  if (const std::string problem = s.validate(); !problem.empty()) {
    inconsistency = "inconsistent hierarchy: " + problem;
    return std::nullopt;
  }
  return s;
}

}  // namespace

Json sceneToJson(const SceneState& state) {
  Json root = Json::object();
  root["format"] = "hybridscape-scene";
  root["version"] = kSceneFormatVersion;
  Json settings = Json::object();
  for (const auto& f : settingsFields()) settings[f.key] = fieldToJson(f, state.settings);
  if (const LutData& lut = state.settings.post.lut; !lut.empty())
    settings["post.lut"] = Json{{"file", lut.fileName}, {"hash", toHex(lut.contentHash)}};
  if (const OcioConfigData& ocio = state.settings.post.ocioConfig; !ocio.empty()) {
    Json files = Json::array();
    for (const OcioFile& f : ocio.files) files.push_back(Json{{"path", f.path}, {"hash", toHex(f.contentHash)}});
    settings["post.ocio_config"] =
        Json{{"file", ocio.fileName}, {"hash", toHex(ocio.contentHash)}, {"files", std::move(files)}};
  }
  root["settings"] = std::move(settings);
  root["roots"] = state.roots;
  Json entities = Json::array();
  for (const auto& [id, e] : state.entities) entities.push_back(entityToJson(e));
  root["entities"] = std::move(entities);
  Json assets = Json::array();
  for (const auto& [id, a] : state.assets) assets.push_back(assetToJson(a));
  root["assets"] = std::move(assets);
  Json materials = Json::array();
  for (const auto& [id, m] : state.materials) materials.push_back(materialToJson(m));
  root["materials"] = std::move(materials);
  Json textures = Json::array();
  for (const auto& [id, t] : state.textures) textures.push_back(textureToJson(t));
  root["textures"] = std::move(textures);
  root["terrains"] = terrainsToJson(state);
  // Foliage types and the manifest of its cells (foliage_file.h).
  if (Json f = foliageToJson(state); !f.is_null()) root["foliage"] = std::move(f);
  // The timeline, in the sequencer's own shape (sequence_json.h).
  root["sequence"] = sequencer::sequenceToJson(state.sequence);
  return root;
}

std::string canonicalJson(const SceneState& state) { return writeJson(sceneToJson(state), -1); }

std::optional<SceneState> sceneFromJson(const Json& json, std::string& error) {
  error.clear();
  Reader r(error);
  return readScene(json, r, error);
}

std::optional<SceneState> sceneFromJsonText(std::string_view text, std::string& error, bool& notJson,
                                            std::vector<std::string>* warnings) {
  error.clear();
  const std::optional<Json> json = parseJson(text, error);
  notJson = !json;
  if (!json) return std::nullopt;
  std::string readerError;
  Reader r(readerError);
  r.warnings = warnings;
  std::optional<SceneState> s = readScene(*json, r, error);
  if (r.failed()) error = jsonErrorIn(text, r);
  return s;
}

}  // namespace hs::scene
