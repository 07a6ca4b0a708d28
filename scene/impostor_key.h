#pragma once
// Whether a mesh asset's stored impostor (MeshAsset::impostor,
// foliage/impostor_images.h) still shows what the renderer would bake now.
// A bake reads the mesh's level 0 and, per material slot, the material's
// base colour, base colour texture, opacity and alpha cut-out
// (shaders/impostor_bake.frag); their hash with the atlas layout is the key
// the bake stores and the renderer compares before drawing stored images.
#include <cstdint>
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

uint64_t impostorSourceKey(const SceneState& state, const MeshAsset& asset);

enum class ImpostorStatus { None, Stored, Stale };
ImpostorStatus impostorStatus(const SceneState& state, const MeshAsset& asset);
// "stored", "stale (its mesh or materials changed since the bake)", "not stored".
std::string impostorStatusText(ImpostorStatus status);

}  // namespace hs::scene
