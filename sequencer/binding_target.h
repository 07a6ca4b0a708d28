#pragma once
// What a binding animates: an entity, a material (a document object of its
// own, by id) or the scene settings. All three are addressed by one 64-bit
// number, `Binding::entity`, so every key edit (KeyRef, move, remove, copy
// and paste), the timeline's rows and the curve view work on material and
// settings tracks exactly as on an entity's, with no second code path.
// Entity ids are whole numbers below 2^53 (the file format's limit), so the
// two top bits are free to say which kind of target a number names:
//
//   entity 7     ->  7
//   material 7   ->  2^62 + 7
//   settings     ->  2^63
//
// In files a binding says the kind in words instead ({"material": 7},
// {"settings": true}; sequence_json.h), so the tag never leaves memory.
#include <cstdint>

namespace hs::sequencer {

enum class TargetKind { Entity, Material, Settings };

inline constexpr uint64_t kMaterialTargetTag = uint64_t(1) << 62;
inline constexpr uint64_t kSettingsTarget = uint64_t(1) << 63;

inline constexpr uint64_t materialTarget(uint64_t materialId) { return kMaterialTargetTag | materialId; }
inline constexpr TargetKind targetKind(uint64_t target) {
  if (target == kSettingsTarget) return TargetKind::Settings;
  return (target & kMaterialTargetTag) != 0 ? TargetKind::Material : TargetKind::Entity;
}
inline constexpr bool isEntityTarget(uint64_t target) { return targetKind(target) == TargetKind::Entity; }
// The material id of a material target (0 for any other target).
inline constexpr uint64_t targetMaterial(uint64_t target) {
  return targetKind(target) == TargetKind::Material ? target & ~kMaterialTargetTag : 0;
}

}  // namespace hs::sequencer
