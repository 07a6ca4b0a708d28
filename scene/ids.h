#pragma once
#include <cstdint>

namespace hs::scene {

// Stable identifiers: commands, selection and file references hold ids, never
// pointers, so undo after delete and restore finds the same entity. 0 = none.
using EntityId = uint64_t;
using AssetId = uint64_t;
constexpr EntityId kNoEntity = 0;
constexpr AssetId kNoAsset = 0;

}  // namespace hs::scene
