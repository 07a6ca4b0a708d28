#pragma once
// Keys and timeline settings as document edits: which track animates a
// field, the value a key takes from an entity or from text, and the
// undoable operations (set keys, remove, replace the sequence after a drag,
// frame rate and range) that the editor's timeline, its key buttons and
// auto key, and `hybridscape-cli key|sequence` all call. Each operation is
// one undo step built with Edit::sequence().
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <QString>

#include "scene/document.h"
#include "scene/fields.h"
#include "sequencer/key_edit.h"

namespace hs::scene {

enum class TrackKind { Scalar, Vector, Rotation, Step };

// What a field's key goes into. The Euler field "transform.rotation_deg"
// is keyed as the quaternion track "transform.rotation" (shortest-path
// interpolation); every other animatable field is its own track.
struct AnimTarget {
  std::string property;  // the track's property
  TrackKind kind = TrackKind::Scalar;
};

// nullopt with `error` if the field is unknown or cannot be animated (names,
// asset references, enums). Material and settings fields are named
// "material.<key>" and "settings.<key>" (object_tracks.h).
std::optional<AnimTarget> animationTarget(std::string_view fieldPath, std::string& error);
// The track property that animates a field path, or "" (rotation_deg -> rotation).
std::string trackPropertyForField(std::string_view fieldPath);

// The entity's value of the target now (what a key button keys).
std::optional<sequencer::PropertyValue> currentKeyValue(const Entity& entity, const AnimTarget& target);
// A value typed for a key: "35", "1,2,3", Euler degrees "0,0,90" for
// rotations, "true"/"false" for visibility.
std::optional<sequencer::PropertyValue> parseKeyValue(const AnimTarget& target, std::string_view text,
                                                      std::string& error);

// Whether the entity has a track for the target, and a key at time t on it.
bool isAnimated(const sequencer::Sequence& sequence, EntityId id, const std::string& property);
bool hasKeyAt(const sequencer::Sequence& sequence, EntityId id, const std::string& property, double t);

// Sets a key in a sequence value (pure): replaces the key at that time
// (keeping its interpolation and tangents unless `interpolation` is given)
// or inserts one; creates the binding and track as needed.
void setKeyIn(sequencer::Sequence& sequence, EntityId id, const std::string& label, const AnimTarget& target,
              double t, const sequencer::PropertyValue& value,
              std::optional<sequencer::Interpolation> interpolation = std::nullopt);

namespace ops {

struct KeyToSet {
  // An entity, or a material or the settings as a binding target
  // (object_tracks.h: materialTarget(id), settingsTarget()).
  EntityId entity = kNoEntity;
  AnimTarget target;
  sequencer::PropertyValue value;
};

// Sets keys at time t as one undo step (one property or a gizmo drag's
// translation, rotation and scale of several entities). Unknown entities
// and values of the wrong kind are refused with `error`, changing nothing.
bool setKeys(Document& doc, const std::vector<KeyToSet>& keys, double t,
             std::optional<sequencer::Interpolation> interpolation, const QString& text,
             const QString& mergeKey = {}, std::string* error = nullptr);
bool removeKeys(Document& doc, const std::vector<sequencer::KeyRef>& keys);
// The whole timeline replaced (a key drag, a curve edit, a paste): one step,
// merged with the steps of the same gesture.
bool replaceSequence(Document& doc, sequencer::Sequence sequence, const QString& text, const QString& mergeKey = {});
bool setFrameRate(Document& doc, sequencer::FrameRate rate);
// Inclusive playback and export range; refuses last < first.
bool setFrameRange(Document& doc, int64_t first, int64_t last);

}  // namespace ops
}  // namespace hs::scene
