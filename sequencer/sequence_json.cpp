#include "sequencer/sequence_json.h"

#include <cmath>

namespace hs::sequencer {

namespace {

JsonValue vec(const glm::dvec3& v) { return JsonValue::Array{v.x, v.y, v.z}; }
JsonValue quat(const glm::dquat& q) { return JsonValue::Array{q.w, q.x, q.y, q.z}; }
JsonValue num(double d) { return JsonValue(d); }

template <class K>
JsonValue keyCommon(const K& k, JsonValue value) {
  JsonValue o(JsonValue::Object{});
  o.set("t", k.time);
  o.set("v", std::move(value));
  return o;
}

template <class K, class ToJson>
JsonValue keyToJson(const K& k, ToJson slopeToJson, JsonValue value) {
  JsonValue o = keyCommon(k, std::move(value));
  if (k.interpolation != Interpolation::Cubic) o.set("interp", interpolationName(k.interpolation));
  if (k.tangentMode != TangentMode::Auto) {
    o.set("tangent", tangentModeName(k.tangentMode));
    if (k.tangentMode == TangentMode::Broken) o.set("in", slopeToJson(k.inSlope));
    o.set("out", slopeToJson(k.outSlope));
  }
  if (k.ease != Ease::None) o.set("ease", easeName(k.ease));
  return o;
}

JsonValue trackToJson(const Track& track) {
  JsonValue o(JsonValue::Object{});
  JsonValue::Array keys;
  std::visit(
      [&](const auto& tr) {
        using T = std::decay_t<decltype(tr)>;
        if constexpr (std::is_same_v<T, ScalarTrack>) {
          o.set("type", "scalar");
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, num, k.value));
        } else if constexpr (std::is_same_v<T, VectorTrack>) {
          o.set("type", "vector");
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, vec, vec(k.value)));
        } else if constexpr (std::is_same_v<T, RotationTrack>) {
          o.set("type", "rotation");
          for (const auto& k : tr.keys) keys.push_back(keyToJson(k, vec, quat(k.value)));
        } else {
          o.set("type", "step");
          for (const auto& k : tr.keys) keys.push_back(keyCommon(k, JsonValue(k.value)));
        }
        o.set("property", tr.property);
      },
      track);
  o.set("keys", std::move(keys));
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

JsonValue pathToJson(const PathFollow& p) {
  JsonValue o(JsonValue::Object{});
  JsonValue::Array points;
  for (const glm::dvec3& v : p.path.points) points.push_back(vec(v));
  o.set("points", std::move(points));
  JsonValue::Array progress;
  for (const auto& k : p.progress.keys) progress.push_back(keyToJson(k, num, k.value));
  o.set("progress", std::move(progress));
  o.set("aim", aimName(p.aim));
  if (p.aim == PathAim::Point) o.set("target_point", vec(p.targetPoint));
  if (p.aim == PathAim::Entity) o.set("target_entity", p.targetEntity);
  if (p.bank) {
    o.set("bank", true);
    o.set("bank_scale", p.bankScale);
    o.set("max_bank_deg", p.maxBankDeg);
  }
  return o;
}

// --- reading ---------------------------------------------------------------

struct Ctx {
  std::string& error;
  bool fail(const std::string& where, const std::string& what) {
    error = where + ": " + what;
    return false;
  }
};

bool readNumber(Ctx& c, const JsonValue* v, const std::string& where, double& out) {
  if (!v || !v->isNumber()) return c.fail(where, "expected a number");
  out = v->asNumber();
  return true;
}

bool readVec(Ctx& c, const JsonValue* v, const std::string& where, glm::dvec3& out) {
  if (!v || !v->isArray() || v->asArray().size() != 3) return c.fail(where, "expected [x, y, z]");
  for (int i = 0; i < 3; ++i)
    if (!readNumber(c, &v->asArray()[size_t(i)], where + "[" + std::to_string(i) + "]", out[i])) return false;
  return true;
}

bool readQuat(Ctx& c, const JsonValue* v, const std::string& where, glm::dquat& out) {
  if (!v || !v->isArray() || v->asArray().size() != 4) return c.fail(where, "expected a quaternion [w, x, y, z]");
  double q[4];
  for (int i = 0; i < 4; ++i)
    if (!readNumber(c, &v->asArray()[size_t(i)], where + "[" + std::to_string(i) + "]", q[i])) return false;
  out = glm::dquat(q[0], q[1], q[2], q[3]);
  if (!(glm::length(out) > 0.0)) return c.fail(where, "the quaternion has zero length");
  return true;
}

bool readString(Ctx& c, const JsonValue* v, const std::string& where, std::string& out) {
  if (!v || !v->isString()) return c.fail(where, "expected a string");
  out = v->asString();
  return true;
}

template <class V, class S, class ReadValue, class ReadSlope>
bool readKey(Ctx& c, const JsonValue& j, const std::string& where, Key<V, S>& k, ReadValue readValue,
             ReadSlope readSlope) {
  if (!j.isObject()) return c.fail(where, "expected a key object {\"t\": ..., \"v\": ...}");
  if (!readNumber(c, j.find("t"), where + ".t", k.time)) return false;
  if (!std::isfinite(k.time)) return c.fail(where + ".t", "time is not finite");
  if (!readValue(c, j.find("v"), where + ".v", k.value)) return false;
  if (const JsonValue* i = j.find("interp")) {
    std::string s;
    if (!readString(c, i, where + ".interp", s)) return false;
    auto v = interpolationFromName(s);
    if (!v) return c.fail(where + ".interp", "unknown interpolation '" + s + "' (constant, linear, cubic)");
    k.interpolation = *v;
  }
  if (const JsonValue* t = j.find("tangent")) {
    std::string s;
    if (!readString(c, t, where + ".tangent", s)) return false;
    auto v = tangentModeFromName(s);
    if (!v) return c.fail(where + ".tangent", "unknown tangent mode '" + s + "' (auto, user, broken)");
    k.tangentMode = *v;
  }
  if (k.tangentMode != TangentMode::Auto) {
    if (!readSlope(c, j.find("out"), where + ".out", k.outSlope)) return false;
    k.inSlope = k.outSlope;
    if (k.tangentMode == TangentMode::Broken && !readSlope(c, j.find("in"), where + ".in", k.inSlope)) return false;
  }
  if (const JsonValue* e = j.find("ease")) {
    std::string s;
    if (!readString(c, e, where + ".ease", s)) return false;
    auto v = easeFromName(s);
    if (!v) return c.fail(where + ".ease", "unknown ease '" + s + "' (none, in, out, in_out)");
    k.ease = *v;
  }
  return true;
}

template <class K, class ReadValue, class ReadSlope>
bool readKeys(Ctx& c, const JsonValue* keys, const std::string& where, std::vector<K>& out, ReadValue rv,
              ReadSlope rs) {
  if (!keys || !keys->isArray()) return c.fail(where, "expected an array of keys");
  for (size_t i = 0; i < keys->asArray().size(); ++i) {
    K k;
    if (!readKey(c, keys->asArray()[i], where + "[" + std::to_string(i) + "]", k, rv, rs)) return false;
    out.push_back(k);
  }
  return true;
}

bool readTrack(Ctx& c, const JsonValue& j, const std::string& where, Track& out) {
  if (!j.isObject()) return c.fail(where, "expected a track object");
  std::string type, property;
  if (!readString(c, j.find("type"), where + ".type", type)) return false;
  if (!readString(c, j.find("property"), where + ".property", property)) return false;
  const JsonValue* keys = j.find("keys");
  const std::string kw = where + ".keys";
  if (type == "scalar") {
    ScalarTrack t{property, {}};
    if (!readKeys(c, keys, kw, t.keys, readNumber, readNumber)) return false;
    out = std::move(t);
  } else if (type == "vector") {
    VectorTrack t{property, {}};
    if (!readKeys(c, keys, kw, t.keys, readVec, readVec)) return false;
    out = std::move(t);
  } else if (type == "rotation") {
    RotationTrack t{property, {}};
    if (!readKeys(c, keys, kw, t.keys, readQuat, readVec)) return false;
    out = std::move(t);
  } else if (type == "step") {
    StepTrack t{property, {}};
    if (!keys || !keys->isArray()) return c.fail(kw, "expected an array of keys");
    for (size_t i = 0; i < keys->asArray().size(); ++i) {
      const JsonValue& kj = keys->asArray()[i];
      const std::string w = kw + "[" + std::to_string(i) + "]";
      StepKey k;
      if (!readNumber(c, kj.find("t"), w + ".t", k.time)) return false;
      const JsonValue* v = kj.find("v");
      if (!v || !v->isBool()) return c.fail(w + ".v", "expected true or false");
      k.value = v->asBool();
      t.keys.push_back(k);
    }
    out = std::move(t);
  } else {
    return c.fail(where + ".type", "unknown track type '" + type + "' (scalar, vector, rotation, step)");
  }
  return true;
}

bool readPath(Ctx& c, const JsonValue& j, const std::string& where, PathFollow& p) {
  if (!j.isObject()) return c.fail(where, "expected a path object");
  const JsonValue* points = j.find("points");
  if (!points || !points->isArray()) return c.fail(where + ".points", "expected an array of [x, y, z]");
  for (size_t i = 0; i < points->asArray().size(); ++i) {
    glm::dvec3 v;
    if (!readVec(c, &points->asArray()[i], where + ".points[" + std::to_string(i) + "]", v)) return false;
    p.path.points.push_back(v);
  }
  if (!readKeys(c, j.find("progress"), where + ".progress", p.progress.keys, readNumber, readNumber)) return false;
  if (const JsonValue* a = j.find("aim")) {
    std::string s;
    if (!readString(c, a, where + ".aim", s)) return false;
    if (s == "tangent") p.aim = PathAim::Tangent;
    else if (s == "point") p.aim = PathAim::Point;
    else if (s == "entity") p.aim = PathAim::Entity;
    else return c.fail(where + ".aim", "unknown aim '" + s + "' (tangent, point, entity)");
  }
  if (p.aim == PathAim::Point && !readVec(c, j.find("target_point"), where + ".target_point", p.targetPoint))
    return false;
  if (p.aim == PathAim::Entity) {
    double id = 0;
    if (!readNumber(c, j.find("target_entity"), where + ".target_entity", id)) return false;
    p.targetEntity = uint64_t(id);
  }
  if (const JsonValue* b = j.find("bank")) {
    if (!b->isBool()) return c.fail(where + ".bank", "expected true or false");
    p.bank = b->asBool();
  }
  if (j.find("bank_scale") && !readNumber(c, j.find("bank_scale"), where + ".bank_scale", p.bankScale)) return false;
  if (j.find("max_bank_deg") && !readNumber(c, j.find("max_bank_deg"), where + ".max_bank_deg", p.maxBankDeg))
    return false;
  return true;
}

}  // namespace

JsonValue sequenceToJson(const Sequence& s) {
  JsonValue o(JsonValue::Object{});
  o.set("format", "hybridscape-sequence");
  o.set("version", kSequenceFormatVersion);
  o.set("rate", JsonValue::Array{JsonValue(s.rate.num), JsonValue(s.rate.den)});
  o.set("start", s.startFrame);
  o.set("end", s.endFrame);
  JsonValue::Array bindings;
  for (const Binding& b : s.bindings) {
    JsonValue bj(JsonValue::Object{});
    bj.set("entity", b.entity);
    bj.set("label", b.label);
    JsonValue::Array tracks;
    for (const Track& t : b.tracks) tracks.push_back(trackToJson(t));
    bj.set("tracks", std::move(tracks));
    if (b.path) bj.set("path", pathToJson(*b.path));
    bindings.push_back(std::move(bj));
  }
  o.set("bindings", std::move(bindings));
  return o;
}

std::optional<Sequence> sequenceFromJson(const JsonValue& j, std::string& error) {
  Ctx c{error};
  Sequence s;
  if (!j.isObject()) {
    c.fail("sequence", "expected an object");
    return std::nullopt;
  }
  if (const JsonValue* f = j.find("format"); !f || !f->isString() || f->asString() != "hybridscape-sequence") {
    c.fail("format", "not a Hybridscape sequence (expected \"format\": \"hybridscape-sequence\")");
    return std::nullopt;
  }
  double version = 0;
  if (!readNumber(c, j.find("version"), "version", version)) return std::nullopt;
  if (version > kSequenceFormatVersion) {
    c.fail("version", "format version " + std::to_string(int64_t(version)) + " is newer than this program reads (" +
                          std::to_string(kSequenceFormatVersion) + "); update Hybridscape");
    return std::nullopt;
  }
  const JsonValue* rate = j.find("rate");
  if (!rate || !rate->isArray() || rate->asArray().size() != 2 || !rate->asArray()[0].isNumber() ||
      !rate->asArray()[1].isNumber() || rate->asArray()[0].asNumber() <= 0 || rate->asArray()[1].asNumber() <= 0) {
    c.fail("rate", "expected [numerator, denominator], e.g. [60, 1] or [60000, 1001]");
    return std::nullopt;
  }
  s.rate = {int64_t(rate->asArray()[0].asNumber()), int64_t(rate->asArray()[1].asNumber())};
  double start = 0, end = 0;
  if (!readNumber(c, j.find("start"), "start", start) || !readNumber(c, j.find("end"), "end", end))
    return std::nullopt;
  s.startFrame = int64_t(start);
  s.endFrame = int64_t(end);
  const JsonValue* bindings = j.find("bindings");
  if (!bindings || !bindings->isArray()) {
    c.fail("bindings", "expected an array");
    return std::nullopt;
  }
  for (size_t i = 0; i < bindings->asArray().size(); ++i) {
    const JsonValue& bj = bindings->asArray()[i];
    const std::string where = "bindings[" + std::to_string(i) + "]";
    Binding b;
    double id = 0;
    if (!bj.isObject()) {
      c.fail(where, "expected an object");
      return std::nullopt;
    }
    if (!readNumber(c, bj.find("entity"), where + ".entity", id)) return std::nullopt;
    b.entity = uint64_t(id);
    if (const JsonValue* l = bj.find("label"); l && !readString(c, l, where + ".label", b.label)) return std::nullopt;
    const JsonValue* tracks = bj.find("tracks");
    if (!tracks || !tracks->isArray()) {
      c.fail(where + ".tracks", "expected an array");
      return std::nullopt;
    }
    for (size_t k = 0; k < tracks->asArray().size(); ++k) {
      Track t;
      if (!readTrack(c, tracks->asArray()[k], where + ".tracks[" + std::to_string(k) + "]", t)) return std::nullopt;
      b.tracks.push_back(std::move(t));
    }
    if (const JsonValue* p = bj.find("path")) {
      PathFollow pf;
      if (!readPath(c, *p, where + ".path", pf)) return std::nullopt;
      b.path = std::move(pf);
    }
    s.bindings.push_back(std::move(b));
  }
  return s;
}

std::string sequenceToJsonText(const Sequence& sequence) { return writeJson(sequenceToJson(sequence)) + "\n"; }

std::optional<Sequence> sequenceFromJsonText(std::string_view text, std::string& error) {
  auto j = readJson(text, error);
  if (!j) return std::nullopt;
  return sequenceFromJson(*j, error);
}

}  // namespace hs::sequencer
