#include "scene/impostor_key.h"

#include <cstring>
#include <vector>

#include "core/content_hash.h"
#include "foliage/impostor_images.h"

namespace hs::scene {
namespace {

// Bumped when the bake's output changes for the same inputs (its shaders).
constexpr uint64_t kBakeVersion = 1;

template <class T>
void add(std::vector<uint8_t>& bytes, const T& v) {
  const size_t at = bytes.size();
  bytes.resize(at + sizeof(T));
  std::memcpy(bytes.data() + at, &v, sizeof(T));
}

}  // namespace

uint64_t impostorSourceKey(const SceneState& state, const MeshAsset& asset) {
  std::vector<uint8_t> bytes;
  add(bytes, kBakeVersion);
  add(bytes, int32_t(foliage::kImpostorFrames));
  add(bytes, int32_t(foliage::kImpostorFramePixels));
  add(bytes, asset.contentHash);
  for (MaterialId id : asset.materialSlots) {
    const Material* m = state.findMaterial(id);
    add(bytes, uint8_t(m != nullptr));
    if (!m) continue;
    add(bytes, m->baseColor);
    add(bytes, m->opacity);
    add(bytes, uint8_t(m->alphaCutout));
    add(bytes, m->alphaThreshold);
    const TextureAsset* t = m->baseColorTexture != kNoTexture ? state.findTexture(m->baseColorTexture) : nullptr;
    add(bytes, uint8_t(t != nullptr));
    if (!t) continue;
    if (t->standalone()) {
      add(bytes, t->contentHash);
    } else {  // a mesh's texture: its mesh's hash stands for it
      const MeshAsset* owner = state.findAsset(t->asset);
      add(bytes, owner ? owner->contentHash : uint64_t(0));
      add(bytes, int32_t(t->meshTexture));
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
