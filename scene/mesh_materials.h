#pragma once
// The document materials of a mesh asset: its material slots (one per
// mesh::Material of its data, then one for submeshes that name none), and
// the materials and textures an import (or the migration of a file from
// before materials were document objects) creates for them, named
// "<asset> / <material>" so users find them.
#include <functional>
#include <string>
#include <vector>

#include "scene/scene_state.h"

namespace hs::scene {

// Slots of `mesh`: its materials, plus one "default" slot if a submesh has
// no (or an out-of-range) material.
size_t materialSlotCount(const mesh::MeshData& mesh);
size_t materialSlotOf(const mesh::MeshData& mesh, const mesh::Submesh& submesh);

struct MeshMaterials {
  std::vector<Material> materials;  // one per slot, ids assigned
  std::vector<TextureAsset> textures;  // one per texture of the mesh, ids assigned
  std::vector<MaterialId> slotIds;   // what MeshAsset::materialSlots becomes
};

struct IdSource {
  std::function<MaterialId()> material;
  std::function<TextureId()> texture;
  // Whether a material name is taken (names get " 2", " 3", ... until free).
  std::function<bool(const std::string&)> nameTaken;
};

// Materials and textures for `asset` (its data must be loaded): base colour
// and texture from each mesh::Material, the rest at their defaults.
MeshMaterials makeMeshMaterials(const MeshAsset& asset, const IdSource& ids);

// Adds them to `state` directly (files from before format 5 on load).
void addMeshMaterials(SceneState& state, AssetId asset);

// Points each mesh texture of `state` at its image in its asset's data
// (after loading). False with `error` if one names a texture the mesh lacks.
bool linkMeshTextures(SceneState& state, std::string& error);

}  // namespace hs::scene
