#include "scene/legacy_hashes.h"

#include <cstring>

namespace hs::scene {
namespace {

struct WordHash {
  uint64_t h = 1469598103934665603ull;
  void mix(uint64_t w) {
    h ^= w;
    h *= 1099511628211ull;
    h ^= h >> 29;
  }
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const uint8_t*>(data);
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      uint64_t w;
      std::memcpy(&w, p + i, 8);
      mix(w);
    }
    uint64_t tail = 0;
    std::memcpy(&tail, p + i, n - i);
    mix(tail ^ (uint64_t(n) << 56));
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    mix(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
};

inline uint64_t finalMix(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  x ^= x >> 33;
  return x;
}

}  // namespace

uint64_t legacyMeshHash(const mesh::MeshData& mesh) {
  WordHash f;
  f.bytes(&mesh.origin, sizeof mesh.origin);
  f.vec(mesh.positions);
  f.vec(mesh.normals);
  f.vec(mesh.uvs);
  f.vec(mesh.indices);
  for (const auto& s : mesh.submeshes) {
    f.bytes(&s.firstIndex, sizeof s.firstIndex);
    f.bytes(&s.indexCount, sizeof s.indexCount);
    f.bytes(&s.material, sizeof s.material);
  }
  for (const auto& m : mesh.materials) {
    f.bytes(m.name.data(), m.name.size());
    f.bytes(&m.baseColor, sizeof m.baseColor);
    f.bytes(&m.diffuseTexture, sizeof m.diffuseTexture);
  }
  for (const auto& t : mesh.textures) {
    f.bytes(t.name.data(), t.name.size());
    f.vec(t.encoded);
    f.bytes(&t.width, sizeof t.width);
    f.bytes(&t.height, sizeof t.height);
    if (t.encoded.empty()) f.vec(t.rgba);
  }
  return f.h;
}

uint64_t legacyTileHash(terrain::TileKind kind, int layer, int tile, const void* data, size_t bytes) {
  uint64_t h = finalMix(0x48535454ull ^ (uint64_t(kind) << 40) ^ (uint64_t(uint32_t(layer)) << 20) ^
                        uint64_t(uint32_t(tile)));
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t lane[4] = {h, h ^ 1, h ^ 2, h ^ 3};
  size_t i = 0;
  for (; i + 32 <= bytes; i += 32)
    for (int k = 0; k < 4; ++k) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * size_t(k), 8);
      lane[k] = (lane[k] ^ w) * 0x9e3779b97f4a7c15ull;
      lane[k] ^= lane[k] >> 29;
    }
  for (; i < bytes; ++i) lane[0] = (lane[0] ^ p[i]) * 0x100000001b3ull;
  h = finalMix(lane[0]) ^ finalMix(lane[1] + 1) ^ finalMix(lane[2] + 2) ^ finalMix(lane[3] + 3);
  return finalMix(h ^ bytes);
}

}  // namespace hs::scene
