#include "scene/sequence_edits.h"

#include <algorithm>
#include <cmath>

#include "scene/edit.h"
#include "scene/emitter_tracks.h"
#include "scene/object_tracks.h"
#include "scene/transform.h"

namespace hs::scene {

namespace {

constexpr std::string_view kRotationTrack = "transform.rotation";
constexpr std::string_view kRotationField = "transform.rotation_deg";

template <class K, class V>
void setInKeys(std::vector<K>& keys, double t, const V& value, std::optional<sequencer::Interpolation> interp) {
  for (K& k : keys)
    if (sequencer::sameKeyTime(k.time, t)) {
      k.value = value;
      if (interp) k.interpolation = *interp;
      return;
    }
  K k;
  k.time = t;
  k.value = value;
  if (interp) k.interpolation = *interp;
  // After the last key at or before t, so keys stay sorted (stable for a
  // deliberate jump made of coincident keys).
  const auto at = std::upper_bound(keys.begin(), keys.end(), t, [](double x, const K& y) { return x < y.time; });
  keys.insert(at, k);
}

bool valueFits(TrackKind kind, const sequencer::PropertyValue& v) {
  switch (kind) {
    case TrackKind::Scalar: return std::holds_alternative<double>(v);
    case TrackKind::Vector: return std::holds_alternative<glm::dvec3>(v);
    case TrackKind::Rotation: return std::holds_alternative<glm::dquat>(v);
    case TrackKind::Step: return std::holds_alternative<bool>(v);
  }
  return false;
}

sequencer::Track emptyTrack(const AnimTarget& target) {
  switch (target.kind) {
    case TrackKind::Scalar: return sequencer::ScalarTrack{target.property, {}};
    case TrackKind::Vector: return sequencer::VectorTrack{target.property, {}};
    case TrackKind::Rotation: return sequencer::RotationTrack{target.property, {}};
    case TrackKind::Step: return sequencer::StepTrack{target.property, {}};
  }
  return sequencer::ScalarTrack{target.property, {}};
}

// A material or settings field's target ("material.roughness",
// "settings.fog_density"); nullopt (error set) for other paths too.
template <class Target>
std::optional<AnimTarget> objectTarget(const FieldInfo<Target>* f, std::string_view path, std::string& error) {
  if (!f) {
    error = "no property '" + std::string(path) + "'";
    return std::nullopt;
  }
  if (f->animatable) switch (f->type) {
      case FieldType::Double: return AnimTarget{std::string(path), TrackKind::Scalar};
      case FieldType::Vec3:
      case FieldType::Color: return AnimTarget{std::string(path), TrackKind::Vector};
      case FieldType::Bool: return AnimTarget{std::string(path), TrackKind::Step};
      default: break;
    }
  error = "'" + std::string(path) + "' cannot be animated (only numbers, colours and on/off)";
  return std::nullopt;
}

// A key's value for a field of an entity, a material or the settings.
template <class Target>
std::optional<sequencer::PropertyValue> parseObjectValue(const FieldInfo<Target>* f, const AnimTarget& target,
                                                         std::string_view text, std::string& error) {
  if (!f) {
    error = "no property '" + target.property + "'";
    return std::nullopt;
  }
  const auto v = parseFieldValue(*f, text, error);
  if (!v) return std::nullopt;
  if (const double* d = std::get_if<double>(&*v)) return sequencer::PropertyValue(*d);
  if (const bool* b = std::get_if<bool>(&*v)) return sequencer::PropertyValue(*b);
  if (const glm::dvec3* x = std::get_if<glm::dvec3>(&*v)) return sequencer::PropertyValue(*x);
  error = "'" + target.property + "' cannot take a key";
  return std::nullopt;
}

bool startsWith(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

std::string trackPropertyForField(std::string_view fieldPath) {
  if (fieldPath == kRotationField) return std::string(kRotationTrack);
  return std::string(fieldPath);
}

std::optional<AnimTarget> animationTarget(std::string_view fieldPath, std::string& error) {
  if (fieldPath == kRotationTrack || fieldPath == kRotationField)
    return AnimTarget{std::string(kRotationTrack), TrackKind::Rotation};
  if (fieldPath == sequencer::kPathProgress)
    return AnimTarget{std::string(fieldPath), TrackKind::Scalar};
  if (startsWith(fieldPath, kMaterialTrackPrefix))
    return objectTarget(findMaterialField(fieldPath.substr(kMaterialTrackPrefix.size())), fieldPath, error);
  if (startsWith(fieldPath, kSettingsTrackPrefix))
    return objectTarget(findSettingsField(fieldPath.substr(kSettingsTrackPrefix.size())), fieldPath, error);
  // An emitter's spawn values (emitter_tracks.h).
  if (isEmitterTrack(fieldPath)) {
    const std::optional<std::string> key = emitterTrackKey(fieldPath, &error);
    if (!key) return std::nullopt;
    return AnimTarget{std::string(fieldPath),
                      particles::spawnValueCount(*key) == 3 ? TrackKind::Vector : TrackKind::Scalar};
  }
  const EntityField* f = findEntityField(fieldPath);
  if (!f) {
    error = "no property '" + std::string(fieldPath) + "'";
    return std::nullopt;
  }
  if (!f->animatable) {
    error = "'" + std::string(fieldPath) + "' cannot be animated";
    return std::nullopt;
  }
  switch (f->type) {
    case FieldType::Double: return AnimTarget{std::string(fieldPath), TrackKind::Scalar};
    case FieldType::Vec3:
    case FieldType::Color: return AnimTarget{std::string(fieldPath), TrackKind::Vector};
    case FieldType::Bool: return AnimTarget{std::string(fieldPath), TrackKind::Step};
    default: break;
  }
  error = "'" + std::string(fieldPath) + "' cannot be animated (only numbers, vectors, colours and on/off)";
  return std::nullopt;
}

std::optional<sequencer::PropertyValue> currentKeyValue(const Entity& entity, const AnimTarget& target) {
  if (target.property == kRotationTrack) return sequencer::PropertyValue(entity.transform.rotation);
  if (const auto key = emitterTrackKey(target.property))
    return entity.particles ? emitterKeyValue(entity.particles->desc, *key) : std::nullopt;
  const EntityField* f = findEntityField(target.property);
  if (!f) return std::nullopt;
  const ComponentInfo* c = findComponent(target.property.substr(0, target.property.find('.')));
  if (c && c->optional && !c->has(entity)) return std::nullopt;
  const FieldValue v = f->get(entity);
  if (const double* d = std::get_if<double>(&v)) return sequencer::PropertyValue(*d);
  if (const bool* b = std::get_if<bool>(&v)) return sequencer::PropertyValue(*b);
  if (const glm::dvec3* x = std::get_if<glm::dvec3>(&v)) return sequencer::PropertyValue(*x);
  return std::nullopt;
}

std::optional<sequencer::PropertyValue> parseKeyValue(const AnimTarget& target, std::string_view text,
                                                      std::string& error) {
  if (target.kind == TrackKind::Rotation) {
    const EntityField* euler = findEntityField(kRotationField);
    const auto v = parseFieldValue(*euler, text, error);
    if (!v) return std::nullopt;
    return sequencer::PropertyValue(fromEulerDegrees(std::get<glm::dvec3>(*v)));
  }
  if (startsWith(target.property, kMaterialTrackPrefix))
    return parseObjectValue(findMaterialTrackField(target.property), target, text, error);
  if (startsWith(target.property, kSettingsTrackPrefix))
    return parseObjectValue(findSettingsTrackField(target.property), target, text, error);
  if (const auto key = emitterTrackKey(target.property)) return parseEmitterKeyValue(*key, text, error);
  return parseObjectValue(findEntityField(target.property), target, text, error);
}

bool isAnimated(const sequencer::Sequence& sequence, EntityId id, const std::string& property) {
  const sequencer::Binding* b = sequence.findBinding(id);
  if (!b) return false;
  const std::vector<std::string> props = sequencer::trackProperties(*b);
  if (std::find(props.begin(), props.end(), property) != props.end()) return true;
  // A path drives translation and rotation.
  return b->path && (property == "transform.translation" || property == kRotationTrack);
}

bool hasKeyAt(const sequencer::Sequence& sequence, EntityId id, const std::string& property, double t) {
  for (double k : sequencer::keyTimes(sequence, id, property))
    if (sequencer::sameKeyTime(k, t)) return true;
  return false;
}

void setKeyIn(sequencer::Sequence& sequence, EntityId id, const std::string& label, const AnimTarget& target,
              double t, const sequencer::PropertyValue& value,
              std::optional<sequencer::Interpolation> interpolation) {
  sequencer::Binding* b = sequence.findBinding(id);
  if (!b) {
    sequence.bindings.push_back(sequencer::Binding{id, label, {}, std::nullopt});
    b = &sequence.bindings.back();
  }
  b->label = label;
  if (target.property == sequencer::kPathProgress) {
    if (b->path && std::holds_alternative<double>(value))
      setInKeys(b->path->progress.keys, t, std::get<double>(value), interpolation);
    return;
  }
  auto track = std::find_if(b->tracks.begin(), b->tracks.end(),
                            [&](const sequencer::Track& x) { return sequencer::trackProperty(x) == target.property; });
  if (track == b->tracks.end()) {
    b->tracks.push_back(emptyTrack(target));
    track = b->tracks.end() - 1;
  }
  std::visit(
      [&](auto& tr) {
        using K = typename std::decay_t<decltype(tr.keys)>::value_type;
        using V = decltype(K::value);
        if (const V* v = std::get_if<V>(&value)) {
          if constexpr (std::is_same_v<K, sequencer::StepKey>) {
            for (K& k : tr.keys)
              if (sequencer::sameKeyTime(k.time, t)) {
                k.value = *v;
                return;
              }
            const auto at = std::upper_bound(tr.keys.begin(), tr.keys.end(), t,
                                             [](double x, const K& y) { return x < y.time; });
            tr.keys.insert(at, K{t, *v});
          } else {
            setInKeys(tr.keys, t, *v, interpolation);
          }
        }
      },
      *track);
}

namespace ops {

bool setKeys(Document& doc, const std::vector<KeyToSet>& keys, double t,
             std::optional<sequencer::Interpolation> interpolation, const QString& text, const QString& mergeKey,
             std::string* error) {
  auto refuse = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!std::isfinite(t)) return refuse("the key time is not a finite number");
  for (const KeyToSet& k : keys) {
    if (!valueFits(k.target.kind, k.value))
      return refuse("a value of the wrong kind for '" + k.target.property + "'");
    if (!propertyFitsTarget(k.entity, k.target.property))
      return refuse("'" + k.target.property + "' is not a field of " +
                    (sequencer::isEntityTarget(k.entity) ? "an entity" : "this target"));
    // A material's or the settings' field (object_tracks.h).
    if (const sequencer::TargetKind kind = sequencer::targetKind(k.entity); kind != sequencer::TargetKind::Entity) {
      if (!targetExists(doc.state(), k.entity))
        return refuse("no material #" + std::to_string(sequencer::targetMaterial(k.entity)));
      const bool fits = kind == sequencer::TargetKind::Material ? findMaterialTrackField(k.target.property) != nullptr
                                                                : findSettingsTrackField(k.target.property) != nullptr;
      if (!fits)
        return refuse("'" + k.target.property + "' is no animatable field of " +
                      (kind == sequencer::TargetKind::Material ? "a material" : "the settings"));
      continue;
    }
    const Entity* e = doc.state().find(k.entity);
    if (!e) return refuse("no entity #" + std::to_string(k.entity));
    if (k.target.property != kRotationTrack && k.target.property != sequencer::kPathProgress) {
      const ComponentInfo* c = findComponent(k.target.property.substr(0, k.target.property.find('.')));
      if (c && c->optional && !c->has(*e))
        return refuse("entity '" + e->name + "' has no " + c->key + " component for '" + k.target.property + "'");
    }
  }
  if (keys.empty()) return false;
  Edit e(doc, text, mergeKey);
  for (const KeyToSet& k : keys)
    setKeyIn(e.sequence(), k.entity,
             sequencer::isEntityTarget(k.entity) ? e.peek(k.entity)->name : targetLabel(doc.state(), k.entity),
             k.target, t, k.value, interpolation);
  return e.commit();
}

bool removeKeys(Document& doc, const std::vector<sequencer::KeyRef>& keys) {
  if (keys.empty()) return false;
  Edit e(doc, keys.size() == 1 ? QString("Delete key") : QString("Delete %1 keys").arg(keys.size()));
  if (sequencer::removeKeys(e.sequence(), keys) == 0) return false;
  return e.commit();
}

bool replaceSequence(Document& doc, sequencer::Sequence sequence, const QString& text, const QString& mergeKey) {
  Edit e(doc, text, mergeKey);
  e.sequence() = std::move(sequence);
  return e.commit();
}

bool setFrameRate(Document& doc, sequencer::FrameRate rate) {
  if (rate.num <= 0 || rate.den <= 0) return false;
  Edit e(doc, QString("Frame rate %1").arg(rate.fps()));
  e.sequence().rate = rate;
  return e.commit();
}

bool setFrameRange(Document& doc, int64_t first, int64_t last) {
  if (last < first) return false;
  Edit e(doc, QString("Frame range %1-%2").arg(first).arg(last));
  e.sequence().startFrame = first;
  e.sequence().endFrame = last;
  return e.commit();
}

}  // namespace ops
}  // namespace hs::scene
