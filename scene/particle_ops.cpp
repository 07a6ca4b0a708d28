#include "scene/particle_ops.h"

#include <algorithm>
#include <cctype>

#include "foliage/surface.h"
#include "particles/emitter.h"
#include "scene/edit.h"
#include "scene/foliage_ground.h"

namespace hs::scene::ops {
namespace {

// "Snow", "Snow 2", ...: entity names are how the CLI finds an emitter.
std::string freeName(const SceneState& s, const std::string& want) {
  if (s.findByName(want) == kNoEntity) return want;
  for (int n = 2;; ++n)
    if (const std::string c = want + " " + std::to_string(n); s.findByName(c) == kNoEntity) return c;
}

}  // namespace

const std::vector<std::string>& emitterListKeys() {
  static const std::vector<std::string> keys = {"rate_keys", "bursts", "wind_keys", "size_over_life",
                                                "colour_over_life"};
  return keys;
}

std::optional<PlacedPreset> placePreset(const SceneState& state, std::string_view preset,
                                        particles::PresetOptions o, bool atGiven, std::string& error) {
  if (!atGiven && o.area) {
    const glm::dvec4 a = *o.area;
    o.at = {0.5 * (a.x + a.z), 0.5 * (a.y + a.w), 0.0};
    const FoliageGround ground(state, false);
    if (const terrain::Terrain* t = ground.ground().terrain)
      if (auto p = foliage::terrainSurface(t->height, {o.at.x, o.at.y})) o.at.z = p->position.z;
  }
  std::vector<particles::EmitterDesc> emitters = particles::makePreset(preset, o, error);
  if (emitters.empty()) return std::nullopt;
  for (const particles::EmitterDesc& d : emitters)
    if (const std::vector<std::string> problems = particles::validate(d); !problems.empty()) {
      error = problems.front();
      return std::nullopt;
    }
  // A one-emitter preset names its emitter ("Snow"); the parent of several
  // takes the given name or the preset's, capitalised ("Torch").
  std::string want = o.name;
  if (want.empty()) {
    want = emitters.size() == 1 ? emitters[0].name : std::string(preset);
    want[0] = char(std::toupper(static_cast<unsigned char>(want[0])));
  }
  PlacedPreset out;
  const std::string top = freeName(state, want);
  const glm::dvec3 base = emitters.front().origin;
  if (emitters.size() > 1) {
    out.group = Entity{};
    out.group->name = top;
    out.group->transform.translation = base;
  }
  for (particles::EmitterDesc& d : emitters) {
    Entity ent;
    ent.name = out.group ? freeName(state, d.name) : top;
    ent.transform.translation = out.group ? d.origin - base : d.origin;
    d.origin = glm::dvec3(0.0);  // the entity carries it
    d.name = ent.name;
    ent.particles = ParticleEmitter{d};
    out.emitters.push_back(std::move(ent));
  }
  return out;
}

EntityId addParticles(Document& doc, std::string_view preset, particles::PresetOptions o, bool atGiven,
                      std::string& error) {
  std::optional<PlacedPreset> placed = placePreset(doc.state(), preset, std::move(o), atGiven, error);
  if (!placed) return kNoEntity;
  const std::string top = placed->group ? placed->group->name : placed->emitters.front().name;
  Edit e(doc, QString("Add %1").arg(QString::fromStdString(top)));
  const EntityId parent = placed->group ? e.addEntity(std::move(*placed->group)) : kNoEntity;
  EntityId first = kNoEntity;
  for (Entity& ent : placed->emitters) {
    const EntityId id = e.addEntity(std::move(ent), parent);
    if (first == kNoEntity) first = id;
  }
  e.commit();
  return parent != kNoEntity ? parent : first;
}

std::optional<Json> parseEmitterValue(const std::string& emitter, std::string_view key, std::string_view text,
                                      std::string& error) {
  const std::string who = "emitter '" + emitter + "', field '" + std::string(key) + "': ";
  const auto& lists = emitterListKeys();
  if (std::find(lists.begin(), lists.end(), key) != lists.end()) {
    Json j = Json::parse(text, nullptr, false);
    if (j.is_discarded()) {
      error = who + "'" + std::string(text) + "' is not a JSON list (e.g. [[0, 100], [5, 400]])";
      return std::nullopt;
    }
    return j;
  }
  const particles::EmitterField* f = particles::findEmitterField(key);
  if (!f) {
    error = "emitter '" + emitter + "': no field '" + std::string(key) + "'";
    return std::nullopt;
  }
  std::string why;
  std::optional<Json> v = parseParam(*f->decl, text, why);
  if (!v) error = who + why;
  return v;
}

namespace {

// The entity whose emitter an edit changes, or null with `error`.
const Entity* emitterEntity(const Document& doc, EntityId id, std::string& error) {
  const Entity* ent = doc.state().find(id);
  if (!ent || !ent->particles) {
    error = ent ? "entity '" + ent->name + "' has no particles component" : "no such entity";
    return nullptr;
  }
  return ent;
}

// Stores `d` as the entity's emitter, validated first (messages name the
// entity as the emitter): one undo step, none when nothing but a stale
// stored name would differ. `changed` says whether a step was pushed.
bool storeEmitter(Document& doc, const Entity& ent, particles::EmitterDesc d, const QString& text,
                  const QString& mergeKey, std::string& error, bool* changed) {
  if (changed) *changed = false;
  d.name = ent.name;
  if (const std::vector<std::string> problems = particles::validate(d); !problems.empty()) {
    error = problems.front();
    return false;
  }
  particles::EmitterDesc now = ent.particles->desc;
  now.name = ent.name;
  if (d == now) return true;
  Edit e(doc, text, mergeKey);
  e.entity(ent.id).particles->desc = std::move(d);
  const bool stored = e.commit();
  if (changed) *changed = stored;
  return true;
}

}  // namespace

bool setEmitter(Document& doc, EntityId id, const particles::EmitterDesc& desc, std::string& error,
                const QString& mergeKey) {
  const Entity* ent = emitterEntity(doc, id, error);
  return ent && storeEmitter(doc, *ent, desc, QString("Edit emitter %1").arg(QString::fromStdString(ent->name)),
                             mergeKey, error, nullptr);
}

bool setEmitterValue(Document& doc, EntityId id, std::string_view key, const Json& value, std::string& error,
                     const QString& mergeKey, bool* changed) {
  if (changed) *changed = false;
  const Entity* ent = emitterEntity(doc, id, error);
  if (!ent) return false;
  particles::EmitterDesc d = ent->particles->desc;
  d.name = ent->name;  // messages name the emitter as the entity is called now
  const auto& lists = emitterListKeys();
  if (std::find(lists.begin(), lists.end(), key) != lists.end()) {
    // Through the file's own reader: the same checks a saved emitter gets.
    Json j = particles::emitterToJson(d);
    j[std::string(key)] = value;
    std::optional<particles::EmitterDesc> read = particles::emitterFromJson(j, error);
    if (!read) return false;
    d = std::move(*read);
  } else if (!particles::setEmitterField(d, key, value, error)) {
    return false;
  }
  return storeEmitter(doc, *ent, std::move(d), QString("Set %1").arg(QString::fromStdString(std::string(key))),
                      mergeKey, error, changed);
}

std::string_view keyedListOf(std::string_view field) {
  if (field == "rate_per_s") return "rate_keys";
  if (field == "wind_m_per_s") return "wind_keys";
  return {};
}

bool keyEmitterField(Document& doc, EntityId id, std::string_view field, double t, const Json& value,
                     std::string& error, bool* changed) {
  if (changed) *changed = false;
  const Entity* ent = emitterEntity(doc, id, error);
  if (!ent) return false;
  const std::string_view list = keyedListOf(field);
  if (list.empty()) {
    error = "emitter '" + ent->name + "', field '" + std::string(field) +
            "': not keyed as a list of the emitter (rate_per_s and wind_m_per_s are)";
    return false;
  }
  particles::EmitterDesc d = ent->particles->desc;
  d.name = ent->name;
  if (!checkParam(particles::keyTimeDecl(), Json(t), error) ||
      !particles::setEmitterField(d, field, value, error)) {  // the value's range, by the field's declaration
    if (error.rfind("emitter '", 0) != 0) error = "emitter '" + d.name + "', field '" + std::string(field) + "': " + error;
    return false;
  }
  Json row = Json::array({t});
  if (value.is_array())
    for (const Json& v : value) row.push_back(v);
  else
    row.push_back(value);
  Json j = particles::emitterToJson(d);
  Json rows = Json::array();
  bool placed = false;
  for (const Json& r : j[std::string(list)]) {
    const double rt = r[0].get<double>();
    if (rt == t) continue;  // replaced
    if (!placed && rt > t) {
      rows.push_back(row);
      placed = true;
    }
    rows.push_back(r);
  }
  if (!placed) rows.push_back(row);
  j[std::string(list)] = rows;
  std::optional<particles::EmitterDesc> read = particles::emitterFromJson(j, error);
  if (!read) return false;
  return storeEmitter(doc, *ent, std::move(*read), QString("Key %1").arg(QString::fromStdString(std::string(field))),
                      {}, error, changed);
}

}  // namespace hs::scene::ops
