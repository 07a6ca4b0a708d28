#include "scene/animation.h"

#include "scene/emitter_tracks.h"
#include "scene/fields.h"
#include "scene/object_tracks.h"

namespace hs::scene {

sequencer::CompiledSequence compileSequence(const SceneState& state) {
  return sequencer::CompiledSequence(state.sequence);
}

bool applyPropertyValue(Entity& entity, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error) {
  // Rotation tracks drive the quaternion itself (shortest-path interpolation),
  // not the Euler-angle field the panel shows.
  if (property == "transform.rotation") {
    const glm::dquat* q = std::get_if<glm::dquat>(&value);
    if (!q) {
      error = "transform.rotation needs a rotation track";
      return false;
    }
    if (glm::length(*q) < 1e-12) {
      error = "transform.rotation: zero quaternion";
      return false;
    }
    entity.transform.rotation = glm::normalize(*q);
    return true;
  }
  const EntityField* field = findEntityField(property);
  if (!field) {
    error = "unknown property '" + property + "'";
    return false;
  }
  const ComponentInfo* component = findComponent(property.substr(0, property.find('.')));
  if (component && component->optional && !component->has(entity)) {
    error = "entity '" + entity.name + "' has no " + component->key + " component for '" + property + "'";
    return false;
  }
  if (!field->animatable) {
    error = "'" + property + "' cannot be animated";
    return false;
  }
  switch (field->type) {
    case FieldType::Double:
      if (const double* d = std::get_if<double>(&value)) return field->set(entity, *d), true;
      break;
    case FieldType::Bool:
      if (const bool* b = std::get_if<bool>(&value)) return field->set(entity, *b), true;
      break;
    case FieldType::Vec3:
    case FieldType::Color:
      if (const glm::dvec3* v = std::get_if<glm::dvec3>(&value)) return field->set(entity, *v), true;
      break;
    default:
      break;
  }
  error = "'" + property + "' got a value of the wrong kind (a track of another type)";
  return false;
}

SceneState animatedState(const SceneState& base, const sequencer::CompiledSequence& compiled, double t,
                         std::vector<std::string>* warnings) {
  SceneState out = base;
  const sequencer::FrameRate rate = compiled.sequence().rate;
  out.time = SceneTime{t, sequencer::frameAtTime(t, rate), rate.fps()};
  if (compiled.sequence().bindings.empty()) return out;
  // Aim targets: an entity's world position with the animated values of its
  // chain applied (the state the sequencer passes in), parents first.
  auto positions = [&base](uint64_t entity, double, const sequencer::SequenceState& animated)
      -> std::optional<glm::dvec3> {
    if (!base.find(entity)) return std::nullopt;
    glm::dmat4 m(1.0);
    for (EntityId id = entity; id != kNoEntity;) {
      const Entity* e = base.find(id);
      if (!e) break;
      Transform local = e->transform;
      if (auto p = animated.vector(id, "transform.translation")) local.translation = *p;
      if (auto q = animated.rotation(id, "transform.rotation")) local.rotation = *q;
      if (auto s = animated.vector(id, "transform.scale")) local.scale = *s;
      m = local.matrix() * m;
      id = e->parent;
    }
    return glm::dvec3(m[3]);
  };
  const sequencer::SequenceState values = sequencer::evaluate(compiled, t, positions);
  std::string error;
  for (const sequencer::PropertySample& s : values.values) {
    // Material and settings tracks (object_tracks.h) write through their
    // fields' setters, which hold the value to the declared range.
    if (sequencer::targetKind(s.entity) == sequencer::TargetKind::Settings) {
      if (!applySettingsValue(out.settings, s.property, s.value, error) && warnings) warnings->push_back(error);
      continue;
    }
    if (sequencer::targetKind(s.entity) == sequencer::TargetKind::Material) {
      auto m = out.materials.find(MaterialId(sequencer::targetMaterial(s.entity)));
      if (m == out.materials.end()) {
        if (warnings)
          warnings->push_back("track for missing material " + std::to_string(sequencer::targetMaterial(s.entity)) +
                              " skipped");
      } else if (!applyMaterialValue(m->second, s.property, s.value, error) && warnings) {
        warnings->push_back("material '" + m->second.name + "': " + error);
      }
      continue;
    }
    // An emitter's spawn values are sampled at each particle's birth
    // (emitter_tracks.h), not written at the frame's time.
    if (isEmitterTrack(s.property)) continue;
    auto it = out.entities.find(s.entity);
    if (it == out.entities.end()) {
      if (warnings) warnings->push_back("track for missing entity " + std::to_string(s.entity) + " skipped");
      continue;
    }
    if (!applyPropertyValue(it->second, s.property, s.value, error) && warnings) warnings->push_back(error);
  }
  // A camera path gives world positions and orientations: an entity under a
  // parent gets them in its parent's (animated) space.
  for (const sequencer::Binding& b : compiled.sequence().bindings) {
    auto it = out.entities.find(b.entity);
    if (!b.path || it == out.entities.end() || it->second.parent == kNoEntity) continue;
    Transform world = it->second.transform;
    world.scale = glm::dvec3(1.0);
    const Transform local = Transform::fromMatrix(glm::inverse(out.worldMatrix(it->second.parent)) * world.matrix());
    it->second.transform.translation = local.translation;
    it->second.transform.rotation = local.rotation;
  }
  if (warnings) warnings->insert(warnings->end(), values.warnings.begin(), values.warnings.end());
  return out;
}

}  // namespace hs::scene
