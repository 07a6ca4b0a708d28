#pragma once
#include <cstdint>

namespace hs::scene {

// Stable identifiers: commands, selection and file references hold ids, never
// pointers, so undo after delete and restore finds the same entity. 0 = none.
using EntityId = uint64_t;
using AssetId = uint64_t;
using TerrainId = uint64_t;  // a terrain's data in the document (scene/terrain_asset.h)
using MaterialId = uint64_t;  // a material of the document (scene/material.h)
using TextureId = uint64_t;   // a texture of the document (scene/material.h)
constexpr EntityId kNoEntity = 0;
constexpr AssetId kNoAsset = 0;
constexpr TerrainId kNoTerrain = 0;
constexpr MaterialId kNoMaterial = 0;
constexpr TextureId kNoTexture = 0;

}  // namespace hs::scene
