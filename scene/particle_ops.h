#pragma once
// Every change to a scene's particle emitters, for the editor's Particles
// panel, the CLI and the demo (docs/particles.md, "In the document"): each
// one undo step, each refusing bad values without touching the document,
// with a message naming the emitter and the field.
#include <optional>
#include <string>
#include <string_view>

#include "core/json.h"
#include "particles/presets.h"
#include "scene/document.h"
#include "scene/entity.h"

namespace hs::scene::ops {

// `preset`'s emitters as entities (ids 0, parent links unset): a parent
// (`group`, when the preset has several emitters) placed at the first
// emitter's origin and one entity per emitter at its origin (relative to
// the parent), each emitter's origin moved into its entity. With no `at`
// but an area, the area's centre at the ground's height there (the first
// visible terrain of `state`; 0 without one). Names are free in `state`.
// Empty with `error` for an unknown preset (the message lists the names).
struct PlacedPreset {
  std::optional<Entity> group;
  std::vector<Entity> emitters;
};
std::optional<PlacedPreset> placePreset(const SceneState& state, std::string_view preset,
                                        particles::PresetOptions options, bool atGiven, std::string& error);

// Adds `preset`'s emitters (particles/presets.h) as entities placed at each
// emitter's origin: one entity for a one-emitter preset, else a parent named
// after the preset with one child per emitter. With no `at` but an area,
// the area's centre at the ground's height there (the first visible
// terrain; 0 without one). Returns the top entity, or kNoEntity with
// `error` (an unknown preset lists the names).
EntityId addParticles(Document& doc, std::string_view preset, particles::PresetOptions options,
                      bool atGiven, std::string& error);

// Sets one of the emitter's fields (a declared key of emitterParamDecls(),
// or a list: rate_keys, bursts, wind_keys, size_over_life,
// colour_over_life) to a JSON value; checked as a file's emitter is.
// false with `error` ("emitter 'Snow', field 'drag_per_s': ...") and the
// document untouched. `changed` says whether the value differed.
bool setEmitterValue(Document& doc, EntityId id, std::string_view key, const Json& value, std::string& error,
                     const QString& mergeKey = {}, bool* changed = nullptr);
// The text of a value for `key` as `set EMITTER particles.KEY TEXT` takes it:
// the declaration's syntax (1.5; 0.5,2; 0,0,-9.81; bounce; true) or JSON for
// a list ("[[0, 100], [5, 400]]").
// Messages name the emitter and the field, as the library's do.
std::optional<Json> parseEmitterValue(const std::string& emitter, std::string_view key, std::string_view text,
                                      std::string& error);
// Replaces the whole emitter (the panel's curve editors), validated first.
bool setEmitter(Document& doc, EntityId id, const particles::EmitterDesc& desc, std::string& error,
                const QString& mergeKey = {});

// The fields whose values over scene time are a keyed list of the emitter
// itself (rate_per_s -> rate_keys, wind_m_per_s -> wind_keys; spawn values
// are keyed as timeline tracks instead: scene/emitter_tracks.h). Empty:
// `field` has no such list.
std::string_view keyedListOf(std::string_view field);
// Keys `field` (keyedListOf) at scene time t: its list gets [t, value...]
// (value: the field's JSON, a number or [x, y, z]), replacing a key at t,
// as one undo step ("Key rate_per_s"): what `key EMITTER
// particles.rate_per_s T VALUE` and the panel's Key at Playhead do. false
// with `error` naming the emitter and the field, the document untouched.
bool keyEmitterField(Document& doc, EntityId id, std::string_view field, double t, const Json& value,
                     std::string& error, bool* changed = nullptr);

// The list keys an emitter has besides its declared fields.
const std::vector<std::string>& emitterListKeys();

}  // namespace hs::scene::ops
