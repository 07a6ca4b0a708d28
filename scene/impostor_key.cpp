#include "scene/impostor_key.h"

#include <vector>

#include "core/content_hash.h"
#include "foliage/byte_io.h"
#include "foliage/impostor_images.h"

namespace hs::scene {
namespace {

// Bumped when the bake's output changes for the same inputs (its shaders,
// the textures it samples). 2: cut-out textures' mips keep their alpha
// coverage (render/material_table.h).
constexpr uint64_t kBakeVersion = 2;

using foliage::byte_io::put;

}  // namespace

uint64_t impostorSourceKey(const SceneState& state, const MeshAsset& asset) {
  std::vector<uint8_t> bytes;
  put(bytes, kBakeVersion);
  put(bytes, int32_t(foliage::kImpostorFrames));
  put(bytes, int32_t(foliage::kImpostorFramePixels));
  put(bytes, asset.contentHash);
  for (MaterialId id : asset.materialSlots) {
    const Material* m = state.findMaterial(id);
    put(bytes, uint8_t(m != nullptr));
    if (!m) continue;
    put(bytes, m->baseColor);
    put(bytes, m->opacity);
    put(bytes, uint8_t(m->alphaCutout));
    put(bytes, m->alphaThreshold);
    const TextureAsset* t = m->baseColorTexture != kNoTexture ? state.findTexture(m->baseColorTexture) : nullptr;
    put(bytes, uint8_t(t != nullptr));
    if (!t) continue;
    if (t->standalone()) {
      put(bytes, t->contentHash);
    } else {  // a mesh's texture: its mesh's hash stands for it
      const MeshAsset* owner = state.findAsset(t->asset);
      put(bytes, owner ? owner->contentHash : uint64_t(0));
      put(bytes, int32_t(t->meshTexture));
    }
  }
  return contentHash(bytes.data(), bytes.size());
}

ImpostorStatus impostorStatus(const SceneState& state, const MeshAsset& asset) {
  if (!asset.impostor) return ImpostorStatus::None;
  return asset.impostor->sourceKey == impostorSourceKey(state, asset) ? ImpostorStatus::Stored : ImpostorStatus::Stale;
}

std::string impostorStatusText(ImpostorStatus status) {
  switch (status) {
    case ImpostorStatus::Stored: return "stored";
    case ImpostorStatus::Stale: return "stale (its mesh or materials changed since the bake)";
    case ImpostorStatus::None: break;
  }
  return "not stored";
}

}  // namespace hs::scene
