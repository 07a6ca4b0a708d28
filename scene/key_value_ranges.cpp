#include "scene/key_value_ranges.h"

#include <type_traits>
#include <variant>

#include "scene/fields.h"

namespace hs::scene {
namespace {

// A value of `field` as its setter leaves it: set on a blank entity that
// has the field's component (rules that compare with other fields of the
// entity do not apply to a key), repaired where the setter alone does not
// make it valid.
FieldValue heldToRange(const ComponentInfo* component, const EntityField& field, const FieldValue& value) {
  Entity blank;
  if (component && component->optional) component->add(blank);
  field.set(blank, value);
  if (field.repair && !fieldValueProblem(field, field.get(blank), static_cast<const Entity*>(nullptr)).empty())
    field.repair(blank);
  return field.get(blank);
}

}  // namespace

void clampKeyValues(SceneState& state, std::vector<std::string>* warnings) {
  const sequencer::FrameRate rate = state.sequence.rate;
  for (sequencer::Binding& binding : state.sequence.bindings) {
    const Entity* entity = state.find(binding.entity);
    const std::string who =
        "entity " + std::to_string(binding.entity) + " '" + (entity ? entity->name : binding.label) + "': ";
    for (sequencer::Track& track : binding.tracks) {
      std::visit(
          [&](auto& t) {
            using T = std::decay_t<decltype(t)>;
            // Rotations are unit quaternions (checked by the sequence
            // reader); on/off keys have no range.
            if constexpr (std::is_same_v<T, sequencer::ScalarTrack> || std::is_same_v<T, sequencer::VectorTrack>) {
              const EntityField* field = findEntityField(t.property);
              if (!field) return;  // path.progress and the like: the sequencer's own checks
              const ComponentInfo* component = findComponent(t.property.substr(0, t.property.find('.')));
              for (auto& key : t.keys) {
                const FieldValue value(key.value);
                const std::string problem = fieldValueProblem(*field, value, static_cast<const Entity*>(nullptr));
                if (problem.empty()) continue;
                const FieldValue held = heldToRange(component, *field, value);
                using V = std::decay_t<decltype(key.value)>;
                if (const V* v = std::get_if<V>(&held)) key.value = *v;
                if (warnings)
                  warnings->push_back(who + t.property + " key at frame " +
                                      std::to_string(sequencer::frameAtTime(key.time, rate)) + ": " +
                                      formatFieldValue(field->type, value, field->enumNames, 6) + " " + problem +
                                      "; now " + formatFieldValue(field->type, held, field->enumNames, 6));
              }
            }
          },
          track);
    }
  }
}

}  // namespace hs::scene
