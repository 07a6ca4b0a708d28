#pragma once
// Timeline tracks on an emitter's spawn values (docs/particles.md, "On the
// timeline"): "particles.<key>" on the emitter entity's binding, <key> one
// of particles::spawnKeys() (speed, size, rotation, spin, spread, cone
// angle, radius, direction, box half extents). A scalar track for numbers
// and MIN,MAX pairs (it moves the pair's centre; the half-width stays), a
// vector track for direction and box_half_m.
//
// They are not written into the entity at a frame's time (animation.h
// skips them): each particle samples them at its own birth time
// (particles::EvaluatorInputs::spawnAt) and keeps what it got, so a value
// keyed up grows the particles born after it and moves none alive, and a
// frame stays a pure function of t. Keys are set like any field's
// (sequence_edits.h: the editor's key button, `hybridscape-cli key`).
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "particles/evaluate.h"
#include "scene/scene_state.h"
#include "sequencer/sequence.h"

namespace hs::scene {

inline constexpr std::string_view kEmitterTrackPrefix = "particles.";

// "particles.size_m" -> "size_m" when size_m is a spawn key; nullopt for
// other paths. `error` (when given) says why a "particles." path is not one.
std::optional<std::string> emitterTrackKey(std::string_view property, std::string* error = nullptr);
bool isEmitterTrack(std::string_view property);  // any "particles." path
// (A key's track is a vector track when particles::spawnValueCount is 3.)

// The emitter's value now as a key (a pair's centre).
std::optional<sequencer::PropertyValue> emitterKeyValue(const particles::EmitterDesc& d, std::string_view key);
// A typed value ("0.08", "0,0,1"), checked against the field's declaration.
std::optional<sequencer::PropertyValue> parseEmitterKeyValue(std::string_view key, std::string_view text,
                                                             std::string& error);

// The emitter's spawn tracks, evaluated at a particle's birth. Null when
// the entity's binding has none.
class EmitterSpawnTracks {
 public:
  static std::shared_ptr<const EmitterSpawnTracks> of(const SceneState& state, EntityId id);
  void apply(double birth, particles::SpawnValues& v) const;
  // `base` with each keyed member at the smallest (first) and the largest
  // (second) value its track takes for births in [t0, t1]
  // (sequencer::valueRange), what particles::widenedForSpawn takes.
  std::pair<particles::SpawnValues, particles::SpawnValues> range(const particles::SpawnValues& base, double t0,
                                                                  double t1) const;
  bool operator==(const EmitterSpawnTracks& o) const { return tracks_ == o.tracks_; }

 private:
  struct SlotTrack {
    int slot = -1;  // particles::spawnSlot of the track's key: apply() runs per particle
    sequencer::Track track;
    bool operator==(const SlotTrack&) const = default;
  };
  std::vector<SlotTrack> tracks_;
};

// Load checks (scene_json): a "particles." track whose key is not a spawn
// key, or whose entity has no emitter, is dropped with a warning naming it.
void checkEmitterTracks(SceneState& state, std::vector<std::string>* warnings);

}  // namespace hs::scene
