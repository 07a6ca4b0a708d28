#pragma once
// Tracks on document objects that are not entities: a material's numeric
// and colour fields ("material.roughness" in the binding of material 7) and
// the scene settings' ("settings.fog_density" in the settings binding).
// The binding's target says which object (sequencer/binding_target.h); the
// fields are those materialFields() and settingsFields() declare, so a
// field added there is animatable here at once, with its range.
//
// Like entity tracks they are evaluated as a pure function of time
// (scene/animation.h), written through the field's setter (which clamps to
// the declared range), clamped on load, and checked on load: a track whose
// material is gone or whose field is unknown is dropped with a message that
// names it, and the rest of the file loads.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/fields.h"
#include "scene/scene_state.h"
#include "sequencer/binding_target.h"
#include "sequencer/sequence.h"

namespace hs::scene {

inline constexpr std::string_view kMaterialTrackPrefix = "material.";
inline constexpr std::string_view kSettingsTrackPrefix = "settings.";

// "material.roughness" -> the material field; nullptr for other paths.
const MaterialField* findMaterialTrackField(std::string_view property);
// "settings.fog_density" -> the settings field; nullptr for other paths.
const SettingsField* findSettingsTrackField(std::string_view property);

// The binding target of a material / of the settings (binding_target.h).
inline uint64_t materialTarget(MaterialId id) { return sequencer::materialTarget(id); }
inline uint64_t settingsTarget() { return sequencer::kSettingsTarget; }

// The name a target's binding carries (an entity's or material's name,
// "Settings"); "" when the state has no such entity or material.
std::string targetLabel(const SceneState& state, uint64_t target);
// Whether the state has the target (settings always exist).
bool targetExists(const SceneState& state, uint64_t target);

// Whether a track property belongs to the kind of target: "material.*"
// on materials, "settings.*" on the settings, neither on entities.
bool propertyFitsTarget(uint64_t target, std::string_view property);

// Writes one sampled value into a material / the settings through the
// field's setter; false with `error` for an unknown or non-animatable field
// or a value of the wrong kind.
bool applyMaterialValue(Material& material, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error);
bool applySettingsValue(SceneSettings& settings, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error);

// The target's value of a material or settings track property now (what a
// key button keys); nullopt for an unknown target or field.
std::optional<sequencer::PropertyValue> currentObjectValue(const SceneState& state, uint64_t target,
                                                           const std::string& property);

// Load checks (scene_json): drops tracks of materials the state lacks and
// tracks whose property names no animatable field of their target's kind
// (and bindings left empty), one warning each ("material track 'Rock'
// (#7) material.roughnes: no such animatable material field; dropped"),
// then clamps their keys to the fields' ranges like clampKeyValues does
// for entities. Bindings of entities are left alone.
void checkObjectTracks(SceneState& state, std::vector<std::string>* warnings);

}  // namespace hs::scene
