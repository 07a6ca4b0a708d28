#include "sequencer/sequence.h"

#include <cmath>

#include "sequencer/binding_target.h"

namespace hs::sequencer {

Binding* Sequence::findBinding(uint64_t entity) {
  for (Binding& b : bindings)
    if (b.entity == entity) return &b;
  return nullptr;
}

const Binding* Sequence::findBinding(uint64_t entity) const {
  return const_cast<Sequence*>(this)->findBinding(entity);
}

const PropertyValue* SequenceState::find(uint64_t entity, std::string_view property) const {
  // Later samples win: a path's pose is appended after the binding's tracks.
  for (auto it = values.rbegin(); it != values.rend(); ++it)
    if (it->entity == entity && it->property == property) return &it->value;
  return nullptr;
}

namespace {
template <class T>
std::optional<T> get(const SequenceState& s, uint64_t e, std::string_view p) {
  const PropertyValue* v = s.find(e, p);
  if (!v || !std::holds_alternative<T>(*v)) return std::nullopt;
  return std::get<T>(*v);
}
}  // namespace

std::optional<double> SequenceState::scalar(uint64_t e, std::string_view p) const { return get<double>(*this, e, p); }
std::optional<glm::dvec3> SequenceState::vector(uint64_t e, std::string_view p) const {
  return get<glm::dvec3>(*this, e, p);
}
std::optional<glm::dquat> SequenceState::rotation(uint64_t e, std::string_view p) const {
  return get<glm::dquat>(*this, e, p);
}
std::optional<bool> SequenceState::flag(uint64_t e, std::string_view p) const { return get<bool>(*this, e, p); }

CompiledSequence::CompiledSequence(Sequence sequence) : sequence_(std::move(sequence)) {
  for (Binding& b : sequence_.bindings) {
    const std::string who =
        targetKind(b.entity) == TargetKind::Settings ? std::string("'Settings'")
        : "'" + b.label + "' (" + (targetKind(b.entity) == TargetKind::Material ? "material #" : "#") +
              std::to_string(b.entity & ~kMaterialTargetTag) + ")";
    for (Track& t : b.tracks) {
      for (const std::string& p : trackProblems(t)) problems_.push_back(who + ": " + p);
      sortKeys(t);
      if (auto* r = std::get_if<RotationTrack>(&t))
        for (RotationKey& k : r->keys) {
          const double len = glm::length(k.value);
          k.value = len > 0.0 && std::isfinite(len) ? k.value / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
        }
    }
    if (b.path) {
      Track progress = b.path->progress;
      sortKeys(progress);
      b.path->progress = std::get<ScalarTrack>(progress);
      if (b.path->path.points.size() < 2)
        problems_.push_back(who + ": the camera path has " + std::to_string(b.path->path.points.size()) +
                            " point(s); it needs two or more to move");
      samplers_.emplace_back(PathSampler(b.path->path.points));
    } else {
      samplers_.emplace_back(std::nullopt);
    }
  }
}

const PathSampler* CompiledSequence::pathSampler(size_t i) const {
  return i < samplers_.size() && samplers_[i] ? &*samplers_[i] : nullptr;
}

SequenceState evaluate(const CompiledSequence& compiled, double t, const EntityPositionFn& positions) {
  const Sequence& seq = compiled.sequence();
  SequenceState state;
  state.time = t;
  // Pass 1: tracks and path positions. Positions never depend on aims, so
  // an aim at another animated entity can read them in pass 2 without cycles.
  for (const Binding& b : seq.bindings) {
    for (const Track& track : b.tracks) {
      std::visit(
          [&](const auto& tr) {
            if (auto v = evaluate(tr, t)) state.values.push_back({b.entity, tr.property, PropertyValue(*v)});
          },
          track);
    }
  }
  // Pass 2: path poses (position and aim).
  for (size_t i = 0; i < seq.bindings.size(); ++i) {
    const Binding& b = seq.bindings[i];
    const PathSampler* sampler = compiled.pathSampler(i);
    if (!b.path || !sampler || sampler->empty()) continue;
    std::optional<glm::dvec3> target;
    if (b.path->aim == PathAim::Entity) {
      if (positions) target = positions(b.path->targetEntity, t, state);
      if (!target) {
        // The target's own path, else its animated translation.
        for (size_t j = 0; j < seq.bindings.size() && !target; ++j) {
          const Binding& other = seq.bindings[j];
          if (other.entity != b.path->targetEntity) continue;
          if (other.path && compiled.pathSampler(j) && !compiled.pathSampler(j)->empty())
            target = evaluatePath(*other.path, *compiled.pathSampler(j), t).position;
          else
            target = state.vector(other.entity, "transform.translation");
        }
      }
      if (!target)
        state.warnings.push_back("'" + b.label + "': aim target #" + std::to_string(b.path->targetEntity) +
                                 " not found; aiming along the path");
    }
    const PathPose pose = evaluatePath(*b.path, *sampler, t, target);
    state.values.push_back({b.entity, "transform.translation", PropertyValue(pose.position)});
    state.values.push_back({b.entity, "transform.rotation", PropertyValue(pose.orientation)});
  }
  return state;
}

SequenceState evaluate(const Sequence& sequence, double t, const EntityPositionFn& positions) {
  return evaluate(CompiledSequence(sequence), t, positions);
}

SequenceState evaluateFrame(const CompiledSequence& sequence, int64_t frame, const EntityPositionFn& positions) {
  return evaluate(sequence, frameTime(frame, sequence.sequence().rate), positions);
}

}  // namespace hs::sequencer
