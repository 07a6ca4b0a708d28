#include "sequencer/sequence_json.h"

#include <cmath>

#include "sequencer/binding_target.h"

namespace hs::sequencer {

namespace {

// Ids and frames are read as whole numbers a double holds exactly (other
// JSON tools read numbers as doubles).
constexpr int64_t kMaxExact = int64_t(1) << 53;

Json vec(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }
Json quat(const glm::dquat& q) { return Json::array({q.w, q.x, q.y, q.z}); }
Json num(double d) { return Json(d); }

template <class K>
Json keyCommon(const K& k, Json value) {
  Json o = Json::object();
  o["t"] = k.time;
  o["v"] = std::move(value);
  return o;
}

template <class K, class ToJson>
Json keyToJson(const K& k, ToJson slopeToJson, Json value) {
  Json o = keyCommon(k, std::move(value));
  if (k.interpolation != Interpolation::Cubic) o["interp"] = interpolationName(k.interpolation);
  if (k.tangentMode != TangentMode::Auto) {
    o["tangent"] = tangentModeName(k.tangentMode);
    if (k.tangentMode == TangentMode::Broken) o["in"] = slopeToJson(k.inSlope);
    o["out"] = slopeToJson(k.outSlope);
  }
  if (k.ease != Ease::None) o["ease"] = easeName(k.ease);
  return o;
}

Json trackToJson(const Track& track) {
  Json o = Json::object();
  Json keys = Json::array();
  std::visit(
      [&](const auto& tr) {
        using T = std::decay_t<decltype(tr)>;
        if constexpr (std::is_same_v<T, ScalarTrack>) {
          o["type"] = "scalar";
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, num, k.value));
        } else if constexpr (std::is_same_v<T, VectorTrack>) {
          o["type"] = "vector";
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, vec, vec(k.value)));
        } else if constexpr (std::is_same_v<T, RotationTrack>) {
          o["type"] = "rotation";
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, vec, quat(k.value)));
        } else {
          o["type"] = "step";
          for (const auto& k : tr.keys) keys.push_back(keyCommon(k, Json(k.value)));
        }
        o["property"] = tr.property;
      },
      track);
  o["keys"] = std::move(keys);
  return o;
}

const char* aimName(PathAim a) {
  switch (a) {
    case PathAim::Tangent: return "tangent";
    case PathAim::Point: return "point";
    case PathAim::Entity: return "entity";
  }
  return "tangent";
}

Json pathToJson(const PathFollow& p) {
  Json o = Json::object();
  Json points = Json::array();
  for (const glm::dvec3& v : p.path.points) points.push_back(vec(v));
  o["points"] = std::move(points);
  Json progress = Json::array();
  for (const auto& k : p.progress.keys) progress.push_back(keyToJson(k, num, k.value));
  o["progress"] = std::move(progress);
  o["aim"] = aimName(p.aim);
  if (p.aim == PathAim::Point) o["target_point"] = vec(p.targetPoint);
  if (p.aim == PathAim::Entity) o["target_entity"] = p.targetEntity;
  if (p.bank) {
    o["bank"] = true;
    o["bank_scale"] = p.bankScale;
    o["max_bank_deg"] = p.maxBankDeg;
  }
  return o;
}

// --- reading ---------------------------------------------------------------
// Each reader takes the value (nullptr: the member is missing, which the
// reader reports) and the JSON path it is at.

bool readNumber(JsonReader& r, const Json* v, const std::string& path, double& out) {
  if (!v) return r.fail(path, "missing");
  return r.number(*v, path, out);
}

bool readVec(JsonReader& r, const Json* v, const std::string& path, glm::dvec3& out) {
  if (!v) return r.fail(path, "missing");
  return r.numbers(*v, path, &out[0], 3, "[x, y, z]");
}

bool readQuat(JsonReader& r, const Json* v, const std::string& path, glm::dquat& out) {
  if (!v) return r.fail(path, "missing");
  double q[4];
  if (!r.numbers(*v, path, q, 4, "a quaternion [w, x, y, z]")) return false;
  out = glm::dquat(q[0], q[1], q[2], q[3]);
  if (!(glm::length(out) > 0.0)) return r.fail(path, "the quaternion has zero length");
  return true;
}

bool readId(JsonReader& r, const Json* v, const std::string& path, uint64_t& out) {
  if (!v) return r.fail(path, "missing");
  int64_t id = 0;
  if (!r.integer(*v, path, id, 0, kMaxExact)) return false;
  out = uint64_t(id);
  return true;
}

// An optional member naming one of a set: absent leaves `out` as it is.
template <class E, class FromName>
bool readName(JsonReader& r, const Json& obj, const std::string& path, const char* key, E& out, FromName fromName,
              const char* what, const char* choices) {
  const Json* m = JsonReader::member(obj, key);
  if (!m) return true;
  std::string s;
  const std::string p = jsonPath(path, key);
  if (!r.string(*m, p, s)) return false;
  const std::optional<E> v = fromName(s);
  if (!v) return r.fail(p, std::string("unknown ") + what + " '" + s + "' (" + choices + ")");
  out = *v;
  return true;
}

template <class V, class S, class ReadValue, class ReadSlope>
bool readKey(JsonReader& r, const Json& j, const std::string& path, Key<V, S>& k, ReadValue readValue,
             ReadSlope readSlope) {
  if (!j.is_object())
    return r.fail(path, std::string("expected a key object {\"t\": ..., \"v\": ...}, not ") + jsonTypeName(j));
  if (!readNumber(r, JsonReader::member(j, "t"), jsonPath(path, "t"), k.time)) return false;
  if (!readValue(r, JsonReader::member(j, "v"), jsonPath(path, "v"), k.value)) return false;
  if (!readName(r, j, path, "interp", k.interpolation, interpolationFromName, "interpolation",
                "constant, linear, cubic") ||
      !readName(r, j, path, "tangent", k.tangentMode, tangentModeFromName, "tangent mode", "auto, user, broken"))
    return false;
  if (k.tangentMode != TangentMode::Auto) {
    if (!readSlope(r, JsonReader::member(j, "out"), jsonPath(path, "out"), k.outSlope)) return false;
    k.inSlope = k.outSlope;
    if (k.tangentMode == TangentMode::Broken &&
        !readSlope(r, JsonReader::member(j, "in"), jsonPath(path, "in"), k.inSlope))
      return false;
  }
  return readName(r, j, path, "ease", k.ease, easeFromName, "ease", "none, in, out, in_out");
}

template <class K, class ReadValue, class ReadSlope>
bool readKeys(JsonReader& r, const Json* keys, const std::string& path, std::vector<K>& out, ReadValue rv,
              ReadSlope rs) {
  if (!keys) return r.fail(path, "missing");
  if (!r.array(*keys, path)) return false;
  for (size_t i = 0; i < keys->size(); ++i) {
    K k;
    if (!readKey(r, (*keys)[i], jsonIndex(path, i), k, rv, rs)) return false;
    out.push_back(k);
  }
  return true;
}

bool readStepKeys(JsonReader& r, const Json* keys, const std::string& path, std::vector<StepKey>& out) {
  if (!keys) return r.fail(path, "missing");
  if (!r.array(*keys, path)) return false;
  for (size_t i = 0; i < keys->size(); ++i) {
    const Json& kj = (*keys)[i];
    const std::string p = jsonIndex(path, i);
    StepKey k;
    if (!r.object(kj, p) || !readNumber(r, JsonReader::member(kj, "t"), jsonPath(p, "t"), k.time)) return false;
    const Json* v = r.required(kj, p, "v");
    if (!v || !r.boolean(*v, jsonPath(p, "v"), k.value)) return false;
    out.push_back(k);
  }
  return true;
}

bool readTrack(JsonReader& r, const Json& j, const std::string& path, Track& out) {
  if (!r.object(j, path)) return false;
  std::string type, property;
  const Json* t = r.required(j, path, "type");
  if (!t || !r.string(*t, jsonPath(path, "type"), type)) return false;
  const Json* p = r.required(j, path, "property");
  if (!p || !r.string(*p, jsonPath(path, "property"), property)) return false;
  const Json* keys = JsonReader::member(j, "keys");
  const std::string kp = jsonPath(path, "keys");
  if (type == "scalar") {
    ScalarTrack tr{property, {}};
    if (!readKeys(r, keys, kp, tr.keys, readNumber, readNumber)) return false;
    out = std::move(tr);
  } else if (type == "vector") {
    VectorTrack tr{property, {}};
    if (!readKeys(r, keys, kp, tr.keys, readVec, readVec)) return false;
    out = std::move(tr);
  } else if (type == "rotation") {
    RotationTrack tr{property, {}};
    if (!readKeys(r, keys, kp, tr.keys, readQuat, readVec)) return false;
    out = std::move(tr);
  } else if (type == "step") {
    StepTrack tr{property, {}};
    if (!readStepKeys(r, keys, kp, tr.keys)) return false;
    out = std::move(tr);
  } else {
    return r.fail(jsonPath(path, "type"), "unknown track type '" + type + "' (scalar, vector, rotation, step)");
  }
  return true;
}

std::optional<PathAim> aimFromName(std::string_view s) {
  if (s == "tangent") return PathAim::Tangent;
  if (s == "point") return PathAim::Point;
  if (s == "entity") return PathAim::Entity;
  return std::nullopt;
}

bool readPath(JsonReader& r, const Json& j, const std::string& path, PathFollow& p) {
  if (!r.object(j, path)) return false;
  const Json* points = r.required(j, path, "points");
  if (!points || !r.array(*points, jsonPath(path, "points"))) return false;
  for (size_t i = 0; i < points->size(); ++i) {
    glm::dvec3 v;
    if (!readVec(r, &(*points)[i], jsonIndex(jsonPath(path, "points"), i), v)) return false;
    p.path.points.push_back(v);
  }
  if (!readKeys(r, JsonReader::member(j, "progress"), jsonPath(path, "progress"), p.progress.keys, readNumber,
                readNumber) ||
      !readName(r, j, path, "aim", p.aim, aimFromName, "aim", "tangent, point, entity"))
    return false;
  if (p.aim == PathAim::Point &&
      !readVec(r, JsonReader::member(j, "target_point"), jsonPath(path, "target_point"), p.targetPoint))
    return false;
  if (p.aim == PathAim::Entity &&
      !readId(r, JsonReader::member(j, "target_entity"), jsonPath(path, "target_entity"), p.targetEntity))
    return false;
  return r.optBoolean(j, path, "bank", p.bank) && r.optNumber(j, path, "bank_scale", p.bankScale) &&
         r.optNumber(j, path, "max_bank_deg", p.maxBankDeg);
}

bool readVersion(JsonReader& r, const Json& j, const std::string& path, int& whole) {
  const Json* f = JsonReader::member(j, "format");
  if (!f || !f->is_string() || f->get<std::string>() != "hybridscape-sequence")
    return r.fail(jsonPath(path, "format"),
                  "not a Hybridscape sequence (expected \"format\": \"hybridscape-sequence\")");
  const std::string vp = jsonPath(path, "version");
  const Json* v = r.required(j, path, "version");
  double version = 0;
  if (!v || !r.number(*v, vp, version)) return false;
  // A newer version says so, however large the number is.
  if (version > kSequenceFormatVersion)
    return r.fail(vp, "format version " + v->dump() + " is newer than this program reads (" +
                          std::to_string(kSequenceFormatVersion) + "); update Hybridscape");
  return r.integer(*v, vp, whole, 1, kSequenceFormatVersion);
}

bool readRate(JsonReader& r, const Json& j, const std::string& path, FrameRate& rate) {
  const std::string rp = jsonPath(path, "rate");
  const Json* v = r.required(j, path, "rate");
  if (!v) return false;
  if (!v->is_array() || v->size() != 2)
    return r.fail(rp, "expected [numerator, denominator], e.g. [60, 1] or [60000, 1001]");
  // Both positive, small enough that frame times never overflow.
  constexpr int64_t kMax = int64_t(1) << 31;
  return r.integer((*v)[0], jsonIndex(rp, 0), rate.num, 1, kMax) &&
         r.integer((*v)[1], jsonIndex(rp, 1), rate.den, 1, kMax);
}

// Which target a binding animates (binding_target.h): "entity": id,
// "material": id (version 2) or "settings": true (version 2), exactly one.
bool readTarget(JsonReader& r, const Json& bj, const std::string& path, int version, Binding& b) {
  const Json* entity = JsonReader::member(bj, "entity");
  const Json* material = version >= 2 ? JsonReader::member(bj, "material") : nullptr;
  const Json* settings = version >= 2 ? JsonReader::member(bj, "settings") : nullptr;
  if (int(entity != nullptr) + int(material != nullptr) + int(settings != nullptr) > 1)
    return r.fail(path, "a binding names one target: \"entity\", \"material\" or \"settings\"");
  if (material) {
    uint64_t id = 0;
    if (!readId(r, material, jsonPath(path, "material"), id)) return false;
    if (id == 0) return r.fail(jsonPath(path, "material"), "material ids start at 1");
    b.entity = materialTarget(id);
    return true;
  }
  if (settings) {
    if (!settings->is_boolean() || !settings->get<bool>())
      return r.fail(jsonPath(path, "settings"), "expected true");
    b.entity = kSettingsTarget;
    return true;
  }
  return readId(r, entity, jsonPath(path, "entity"), b.entity);
}

bool readBinding(JsonReader& r, const Json& bj, const std::string& path, int version, Binding& b) {
  if (!r.object(bj, path) || !readTarget(r, bj, path, version, b) || !r.optString(bj, path, "label", b.label))
    return false;
  const std::string tp = jsonPath(path, "tracks");
  const Json* tracks = r.required(bj, path, "tracks");
  if (!tracks || !r.array(*tracks, tp)) return false;
  for (size_t k = 0; k < tracks->size(); ++k) {
    Track t;
    if (!readTrack(r, (*tracks)[k], jsonIndex(tp, k), t)) return false;
    b.tracks.push_back(std::move(t));
  }
  if (const Json* p = JsonReader::member(bj, "path")) {
    PathFollow pf;
    if (!readPath(r, *p, jsonPath(path, "path"), pf)) return false;
    b.path = std::move(pf);
  }
  return true;
}

}  // namespace

Json sequenceToJson(const Sequence& s) {
  Json o = Json::object();
  o["format"] = "hybridscape-sequence";
  // Version 1 when every binding animates an entity, so such files still
  // open in builds from before material and settings tracks.
  bool entitiesOnly = true;
  for (const Binding& b : s.bindings) entitiesOnly = entitiesOnly && isEntityTarget(b.entity);
  o["version"] = !s.cuts.empty() ? 3 : entitiesOnly ? 1 : 2;
  o["rate"] = Json::array({s.rate.num, s.rate.den});
  o["start"] = s.startFrame;
  o["end"] = s.endFrame;
  Json bindings = Json::array();
  for (const Binding& b : s.bindings) {
    Json bj = Json::object();
    switch (targetKind(b.entity)) {
      case TargetKind::Entity: bj["entity"] = b.entity; break;
      case TargetKind::Material: bj["material"] = targetMaterial(b.entity); break;
      case TargetKind::Settings: bj["settings"] = true; break;
    }
    bj["label"] = b.label;
    Json tracks = Json::array();
    for (const Track& t : b.tracks) tracks.push_back(trackToJson(t));
    bj["tracks"] = std::move(tracks);
    if (b.path) bj["path"] = pathToJson(*b.path);
    bindings.push_back(std::move(bj));
  }
  o["bindings"] = std::move(bindings);
  if (!s.cuts.empty()) {
    Json cuts = Json::array();
    for (const CameraCut& c : s.cuts) {
      Json cj = {{"camera", c.camera}, {"start", c.start}, {"end", c.end}};
      if (c.transition != Transition::Cut) {
        cj["transition"] = transitionName(c.transition);
        cj["frames"] = c.transitionFrames;
        cj["ease"] = easeName(c.ease);
      }
      cuts.push_back(std::move(cj));
    }
    o["cuts"] = std::move(cuts);
  }
  return o;
}

bool readSequence(JsonReader& r, const Json& j, const std::string& path, Sequence& s) {
  s = Sequence{};
  int version = 0;
  if (!r.object(j, path) || !readVersion(r, j, path, version) || !readRate(r, j, path, s.rate)) return false;
  for (auto [key, frame] : {std::pair{"start", &s.startFrame}, {"end", &s.endFrame}}) {
    const Json* v = r.required(j, path, key);
    if (!v || !r.integer(*v, jsonPath(path, key), *frame, -kMaxExact, kMaxExact)) return false;
  }
  const std::string bp = jsonPath(path, "bindings");
  const Json* bindings = r.required(j, path, "bindings");
  if (!bindings || !r.array(*bindings, bp)) return false;
  for (size_t i = 0; i < bindings->size(); ++i) {
    Binding b;
    if (!readBinding(r, (*bindings)[i], jsonIndex(bp, i), version, b)) return false;
    s.bindings.push_back(std::move(b));
  }
  // Camera cuts (version 3): their values read here; whether they fit
  // together and name cameras is camera_cuts.h's cutsProblem, asked where
  // they are rendered (a file with a cut on a deleted camera still opens).
  if (const Json* cuts = JsonReader::member(j, "cuts"); cuts && !cuts->is_null()) {
    const std::string cp = jsonPath(path, "cuts");
    if (!r.array(*cuts, cp)) return false;
    for (size_t i = 0; i < cuts->size(); ++i) {
      const Json& cj = (*cuts)[i];
      const std::string p = jsonIndex(cp, i);
      CameraCut c;
      int64_t camera = 0;
      if (!r.object(cj, p)) return false;
      for (auto [key, out] : {std::pair{"camera", &camera}, {"start", &c.start}, {"end", &c.end}}) {
        const Json* v = r.required(cj, p, key);
        if (!v || !r.integer(*v, jsonPath(p, key), *out, key == std::string("camera") ? 1 : -kMaxExact, kMaxExact))
          return false;
      }
      c.camera = uint64_t(camera);
      if (const Json* t = JsonReader::member(cj, "transition")) {
        std::string name;
        if (!r.string(*t, jsonPath(p, "transition"), name)) return false;
        const std::optional<Transition> kind = transitionFromName(name);
        if (!kind) return r.fail(jsonPath(p, "transition"), "unknown transition '" + name + "' (" + transitionNames() + ")");
        c.transition = *kind;
        const Json* frames = r.required(cj, p, "frames");
        if (!frames || !r.integer(*frames, jsonPath(p, "frames"), c.transitionFrames, 0, kMaxExact)) return false;
        if (const Json* e = JsonReader::member(cj, "ease")) {
          std::string ease;
          if (!r.string(*e, jsonPath(p, "ease"), ease)) return false;
          const std::optional<Ease> value = easeFromName(ease);
          if (!value) return r.fail(jsonPath(p, "ease"), "unknown ease '" + ease + "' (none, in, out, in_out)");
          c.ease = *value;
        }
      }
      s.cuts.push_back(c);
    }
  }
  return true;
}

std::optional<Sequence> sequenceFromJson(const Json& json, std::string& error) {
  JsonReader r(error);
  Sequence s;
  if (!readSequence(r, json, "", s)) return std::nullopt;
  return s;
}

std::string sequenceToJsonText(const Sequence& sequence) { return writeJson(sequenceToJson(sequence)) + "\n"; }

std::optional<Sequence> sequenceFromJsonText(std::string_view text, std::string& error) {
  const std::optional<Json> j = parseJson(text, error);
  if (!j) return std::nullopt;
  std::string readerError;
  JsonReader r(readerError);
  Sequence s;
  if (!readSequence(r, *j, "", s)) {
    error = jsonErrorIn(text, r);
    return std::nullopt;
  }
  return s;
}

}  // namespace hs::sequencer
