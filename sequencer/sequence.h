#pragma once
// A sequence: the tracks of every animated entity, grouped by entity (a
// binding), the frame rate and the playback/export range. Evaluating it at
// a time t is a pure function (DESIGN.md, "Time and determinism"): no state
// carried from one frame to the next, so scrubbing, export and any farm
// chunk see the same values at the same t.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sequencer/camera_cuts.h"
#include "sequencer/camera_path.h"
#include "sequencer/frame_range.h"
#include "sequencer/track.h"

namespace hs::sequencer {

// The tracks of one entity. `entity` is scene::EntityId (ids are stable
// across renames and undo), or a material or the scene settings as a tagged
// target (binding_target.h); `label` is the name shown in the timeline and
// in messages, refreshed by the scene when the entity is renamed.
struct Binding {
  uint64_t entity = 0;
  std::string label;
  std::vector<Track> tracks;
  // When set, the entity's world position and orientation come from the
  // path ("transform.translation", "transform.rotation" in the result),
  // in place of tracks on those properties.
  std::optional<PathFollow> path;
  bool operator==(const Binding&) const = default;
};

struct Sequence {
  FrameRate rate{60, 1};
  int64_t startFrame = 0;     // playback and export range, inclusive
  int64_t endFrame = 35999;
  std::vector<Binding> bindings;
  // The camera-cut track (camera_cuts.h), sorted by start; empty: the
  // render's own camera throughout.
  std::vector<CameraCut> cuts;
  bool operator==(const Sequence&) const = default;

  Binding* findBinding(uint64_t entity);
  const Binding* findBinding(uint64_t entity) const;
};

using PropertyValue = std::variant<double, glm::dvec3, glm::dquat, bool>;

struct PropertySample {
  uint64_t entity = 0;
  std::string property;
  PropertyValue value;
};

// Everything the sequence sets at one time: what the scene applies before
// rendering a frame (scene/animation.h writes each sample through
// scene/fields.h, and "transform.rotation" straight into Transform::rotation).
struct SequenceState {
  double time = 0.0;
  std::vector<PropertySample> values;    // in binding order, tracks in track order
  std::vector<std::string> warnings;     // e.g. an aim target that could not be found

  const PropertyValue* find(uint64_t entity, std::string_view property) const;
  std::optional<double> scalar(uint64_t entity, std::string_view property) const;
  std::optional<glm::dvec3> vector(uint64_t entity, std::string_view property) const;
  std::optional<glm::dquat> rotation(uint64_t entity, std::string_view property) const;
  std::optional<bool> flag(uint64_t entity, std::string_view property) const;
};

// World position of an entity at time t, for paths that aim at an entity.
// scene/ supplies one that walks the hierarchy with the sequence's values
// applied. nullopt: unknown entity.
using EntityPositionFn = std::function<std::optional<glm::dvec3>(uint64_t entity, double t,
                                                                 const SequenceState& animated)>;

// A sequence made ready for evaluation: keys sorted, rotations normalized,
// path splines built. Immutable, cheap to evaluate from several threads.
class CompiledSequence {
 public:
  CompiledSequence() = default;
  explicit CompiledSequence(Sequence sequence);
  const Sequence& sequence() const { return sequence_; }
  const PathSampler* pathSampler(size_t bindingIndex) const;
  // Problems found while compiling (unsorted keys were sorted, a rotation was
  // normalized, a path has fewer than two points, ...).
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  Sequence sequence_;
  std::vector<std::optional<PathSampler>> samplers_;
  std::vector<std::string> problems_;
};

// The pure evaluation. Without `positions`, an aim at an entity uses that
// entity's animated "transform.translation" (or its path) from the same
// state, taken as a world position; otherwise the fallback is to aim along
// the path, with a warning in the state.
SequenceState evaluate(const CompiledSequence& sequence, double t, const EntityPositionFn& positions = {});
// Convenience for one-off calls; compiles on every call.
SequenceState evaluate(const Sequence& sequence, double t, const EntityPositionFn& positions = {});
SequenceState evaluateFrame(const CompiledSequence& sequence, int64_t frame, const EntityPositionFn& positions = {});

}  // namespace hs::sequencer
