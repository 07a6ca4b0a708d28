#include "scene/object_tracks.h"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace hs::scene {
namespace {

template <class Target>
const FieldInfo<Target>* animatableField(const FieldInfo<Target>* f) {
  if (!f || !f->animatable) return nullptr;
  switch (f->type) {
    case FieldType::Double:
    case FieldType::Bool:
    case FieldType::Vec3:
    case FieldType::Color: return f;
    default: return nullptr;
  }
}

std::optional<std::string_view> afterPrefix(std::string_view property, std::string_view prefix) {
  if (property.substr(0, prefix.size()) != prefix) return std::nullopt;
  return property.substr(prefix.size());
}

// The key's value type for a field (a key of another type is refused).
template <class Target>
bool applyField(const FieldInfo<Target>& field, Target& target, const sequencer::PropertyValue& value) {
  switch (field.type) {
    case FieldType::Double:
      if (const double* d = std::get_if<double>(&value)) return field.set(target, *d), true;
      return false;
    case FieldType::Bool:
      if (const bool* b = std::get_if<bool>(&value)) return field.set(target, *b), true;
      return false;
    case FieldType::Vec3:
    case FieldType::Color:
      if (const glm::dvec3* v = std::get_if<glm::dvec3>(&value)) return field.set(target, *v), true;
      return false;
    default: return false;
  }
}

template <class Target>
bool applyValue(const FieldInfo<Target>* field, Target& target, const std::string& property,
                const sequencer::PropertyValue& value, std::string& error) {
  if (!field) {
    error = "unknown property '" + property + "'";
    return false;
  }
  if (!applyField(*field, target, value)) {
    error = "'" + property + "' got a value of the wrong kind (a track of another type)";
    return false;
  }
  return true;
}

template <class Target>
std::optional<sequencer::PropertyValue> valueOf(const FieldInfo<Target>* field, const Target& target) {
  if (!field) return std::nullopt;
  const FieldValue v = field->get(target);
  if (const double* d = std::get_if<double>(&v)) return sequencer::PropertyValue(*d);
  if (const bool* b = std::get_if<bool>(&v)) return sequencer::PropertyValue(*b);
  if (const glm::dvec3* x = std::get_if<glm::dvec3>(&v)) return sequencer::PropertyValue(*x);
  return std::nullopt;
}

// Keys held to the field's range the way its setter holds a value, with a
// warning per key changed (as clampKeyValues words them for entities).
template <class Target>
void clampKeys(const FieldInfo<Target>& field, sequencer::Track& track, const std::string& who,
               sequencer::FrameRate rate, std::vector<std::string>* warnings) {
  std::visit(
      [&](auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, sequencer::ScalarTrack> || std::is_same_v<T, sequencer::VectorTrack>) {
          for (auto& key : t.keys) {
            const FieldValue value(key.value);
            const std::string problem = fieldValueProblem(field, value, static_cast<const Target*>(nullptr));
            if (problem.empty()) continue;
            Target blank{};
            field.set(blank, value);
            const FieldValue held = field.get(blank);
            using V = std::decay_t<decltype(key.value)>;
            if (const V* v = std::get_if<V>(&held)) key.value = *v;
            if (warnings)
              warnings->push_back(who + t.property + " key at frame " +
                                  std::to_string(sequencer::frameAtTime(key.time, rate)) + ": " +
                                  formatFieldValue(field.type, value, field.enumNames, 6) + " " + problem + "; now " +
                                  formatFieldValue(field.type, held, field.enumNames, 6));
          }
        }
      },
      track);
}

// Whether a track's type carries the field's values (a scalar track on a
// colour is as unusable as an unknown field).
template <class Target>
bool trackFits(const FieldInfo<Target>& field, const sequencer::Track& track) {
  switch (field.type) {
    case FieldType::Double: return std::holds_alternative<sequencer::ScalarTrack>(track);
    case FieldType::Bool: return std::holds_alternative<sequencer::StepTrack>(track);
    case FieldType::Vec3:
    case FieldType::Color: return std::holds_alternative<sequencer::VectorTrack>(track);
    default: return false;
  }
}

}  // namespace

const MaterialField* findMaterialTrackField(std::string_view property) {
  const auto key = afterPrefix(property, kMaterialTrackPrefix);
  return key ? animatableField(findMaterialField(*key)) : nullptr;
}

const SettingsField* findSettingsTrackField(std::string_view property) {
  const auto key = afterPrefix(property, kSettingsTrackPrefix);
  return key ? animatableField(findSettingsField(*key)) : nullptr;
}

std::string targetLabel(const SceneState& state, uint64_t target) {
  switch (sequencer::targetKind(target)) {
    case sequencer::TargetKind::Entity: {
      const Entity* e = state.find(target);
      return e ? e->name : std::string();
    }
    case sequencer::TargetKind::Material: {
      const Material* m = state.findMaterial(MaterialId(sequencer::targetMaterial(target)));
      return m ? m->name : std::string();
    }
    case sequencer::TargetKind::Settings: return "Settings";
  }
  return {};
}

bool targetExists(const SceneState& state, uint64_t target) {
  switch (sequencer::targetKind(target)) {
    case sequencer::TargetKind::Entity: return state.find(target) != nullptr;
    case sequencer::TargetKind::Material:
      return state.findMaterial(MaterialId(sequencer::targetMaterial(target))) != nullptr;
    case sequencer::TargetKind::Settings: return true;
  }
  return false;
}

bool propertyFitsTarget(uint64_t target, std::string_view property) {
  const bool materialPath = afterPrefix(property, kMaterialTrackPrefix).has_value();
  const bool settingsPath = afterPrefix(property, kSettingsTrackPrefix).has_value();
  switch (sequencer::targetKind(target)) {
    case sequencer::TargetKind::Entity: return !materialPath && !settingsPath;
    case sequencer::TargetKind::Material: return materialPath;
    case sequencer::TargetKind::Settings: return settingsPath;
  }
  return false;
}

bool applyMaterialValue(Material& material, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error) {
  return applyValue(findMaterialTrackField(property), material, property, value, error);
}

bool applySettingsValue(SceneSettings& settings, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error) {
  return applyValue(findSettingsTrackField(property), settings, property, value, error);
}

std::optional<sequencer::PropertyValue> currentObjectValue(const SceneState& state, uint64_t target,
                                                           const std::string& property) {
  switch (sequencer::targetKind(target)) {
    case sequencer::TargetKind::Material: {
      const Material* m = state.findMaterial(MaterialId(sequencer::targetMaterial(target)));
      return m ? valueOf(findMaterialTrackField(property), *m) : std::nullopt;
    }
    case sequencer::TargetKind::Settings: return valueOf(findSettingsTrackField(property), state.settings);
    case sequencer::TargetKind::Entity: break;
  }
  return std::nullopt;
}

void checkObjectTracks(SceneState& state, std::vector<std::string>* warnings) {
  const sequencer::FrameRate rate = state.sequence.rate;
  auto warn = [&](const std::string& text) {
    if (warnings) warnings->push_back(text);
  };
  for (sequencer::Binding& b : state.sequence.bindings) {
    const sequencer::TargetKind kind = sequencer::targetKind(b.entity);
    if (kind == sequencer::TargetKind::Entity) continue;
    const bool material = kind == sequencer::TargetKind::Material;
    const uint64_t materialId = sequencer::targetMaterial(b.entity);
    const std::string who = material ? "material track '" + b.label + "' (#" + std::to_string(materialId) + ") "
                                     : std::string("settings track ");
    if (material && !state.findMaterial(MaterialId(materialId))) {
      for (const sequencer::Track& t : b.tracks)
        warn(who + sequencer::trackProperty(t) + ": the scene has no material " + std::to_string(materialId) +
             "; dropped");
      b.tracks.clear();
      b.path.reset();
      continue;
    }
    if (b.path) {
      warn(who + "has a camera path, which only entities follow; dropped");
      b.path.reset();
    }
    if (material) b.label = state.findMaterial(MaterialId(materialId))->name;  // the name it has now
    else b.label = "Settings";
    std::erase_if(b.tracks, [&](sequencer::Track& t) {
      const std::string& property = sequencer::trackProperty(t);
      const MaterialField* mf = material ? findMaterialTrackField(property) : nullptr;
      const SettingsField* sf = material ? nullptr : findSettingsTrackField(property);
      if ((material && !mf) || (!material && !sf)) {
        warn(who + property + ": no such animatable " + (material ? "material" : "settings") +
             " field (numbers, colours and on/off are); dropped");
        return true;
      }
      if ((mf && !trackFits(*mf, t)) || (sf && !trackFits(*sf, t))) {
        warn(who + property + ": a track of the wrong type for this field; dropped");
        return true;
      }
      const std::string prefix = material ? "material '" + b.label + "': " : std::string("settings: ");
      if (mf) clampKeys(*mf, t, prefix, rate, warnings);
      if (sf) clampKeys(*sf, t, prefix, rate, warnings);
      return false;
    });
  }
  std::erase_if(state.sequence.bindings, [](const sequencer::Binding& b) {
    return !sequencer::isEntityTarget(b.entity) && b.tracks.empty() && !b.path;
  });
}

}  // namespace hs::scene
