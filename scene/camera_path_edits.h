#pragma once
// Camera paths as document edits: an entity (a camera, usually) made to
// follow a path, its points inserted, removed and moved, its aim, banking and
// timing changed, the path removed. The editor's path tools (app/path_*,
// app/camera_path_panel.*) and `hybridscape-cli path` call these; each is one
// undo step built with Edit::sequence(). Paths live in the sequence
// (sequencer::PathFollow on the entity's binding), in world space.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <QString>

#include "scene/document.h"
#include "sequencer/camera_path_edit.h"

namespace hs::scene {

// The path the entity follows, or nullptr.
const sequencer::PathFollow* findPath(const SceneState& state, EntityId id);

// The sequence's playback range in seconds: what a new path covers at
// constant speed unless told otherwise.
std::pair<double, double> playbackTimes(const sequencer::Sequence& sequence);

// The entity's location keys as world points (through its parent as it
// stands), with the times of the first and last key: a path "from the
// location keys" runs through them over the same time.
struct LocationKeyPoints {
  std::vector<glm::dvec3> points;
  double first = 0.0, last = 0.0;
};
LocationKeyPoints locationKeyPoints(const SceneState& state, EntityId id);

// sequencer::pathProblem, plus what only the scene knows: an entity target
// that does not exist, or is the entity itself.
std::optional<std::string> pathProblem(const SceneState& state, EntityId id, const sequencer::PathFollow& follow);

namespace ops {

// Makes `id` follow `follow` (replacing the path it had), one undo step.
// The entity's location and rotation tracks go: the path drives both, so
// their keys would only lie hidden under it (undo brings them back).
// Refused, changing nothing, with `error` for an unknown entity or a path
// that cannot be followed.
bool setPath(Document& doc, EntityId id, sequencer::PathFollow follow, const QString& text,
             std::string* error = nullptr);
// Changes the entity's path through `change`, one undo step (steps with the
// same non-empty `mergeKey` fold into one: a drag). Refused if the entity
// follows no path or the result cannot be followed.
bool editPath(Document& doc, EntityId id, const QString& text,
              const std::function<void(sequencer::PathFollow&)>& change, const QString& mergeKey = {},
              std::string* error = nullptr);
// The entity stops following its path (its binding goes too when it has no
// tracks left). The entity's own transform was never changed by the path.
bool removePath(Document& doc, EntityId id, std::string* error = nullptr);

// Points: `index` counts from 0. Insert puts the point before `index`
// (size(): at the end); removing refuses to leave fewer than two points.
bool insertPathPoint(Document& doc, EntityId id, size_t index, const glm::dvec3& point, std::string* error = nullptr);
bool removePathPoint(Document& doc, EntityId id, size_t index, std::string* error = nullptr);
bool movePathPoint(Document& doc, EntityId id, size_t index, const glm::dvec3& point, const QString& mergeKey = {},
                   std::string* error = nullptr);
// Replaces the progress keys: the path covered at constant speed over
// [t0, t1] (`ease` InOut: with a soft start and stop).
bool setPathTiming(Document& doc, EntityId id, double t0, double t1, sequencer::Ease ease = sequencer::Ease::None,
                   std::string* error = nullptr);

}  // namespace ops
}  // namespace hs::scene
