#include "mesh/mesh_data.h"

#include <cmath>
#include <cstring>

namespace hs::mesh {

void Bounds::extend(const glm::vec3& p) {
  if (empty) {
    min = max = p;
    empty = false;
  } else {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
}

Bounds MeshData::bounds() const {
  Bounds b;
  for (const auto& p : positions) b.extend(p);
  return b;
}

size_t MeshData::memoryBytes() const {
  size_t bytes = positions.size() * sizeof(glm::vec3) + normals.size() * sizeof(glm::vec3) +
                 uvs.size() * sizeof(glm::vec2) + indices.size() * sizeof(uint32_t);
  for (const auto& t : textures) bytes += t.rgba.size() + t.encoded.size();
  return bytes;
}

void computeVertexNormals(MeshData& mesh) {
  std::vector<glm::dvec3> acc(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
    // The un-normalised cross product weights each face by its area.
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
    acc[a] += n;
    acc[b] += n;
    acc[c] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t i = 0; i < acc.size(); ++i) {
    const double len = glm::length(acc[i]);
    mesh.normals[i] = len > 0.0 ? glm::vec3(acc[i] / len) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

void recenter(MeshData& mesh) {
  const Bounds b = mesh.bounds();
  if (b.empty) return;
  // Shift by a value rounded to 1/1024 m: small enough not to matter for
  // precision, round enough that the new origin prints cleanly.
  const glm::dvec3 c = glm::round(glm::dvec3(b.center()) * 1024.0) / 1024.0;
  const glm::vec3 shift(c);
  for (auto& p : mesh.positions) p -= shift;
  mesh.origin += glm::dvec3(shift);
}

namespace {
// FNV-1a style, but over 8-byte words so hashing a 50M-triangle scan before a
// save costs tens of milliseconds, not seconds. Not cryptographic: it only
// answers "did this blob change since the last save".
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
}  // namespace

uint64_t contentHash(const MeshData& mesh) {
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

}  // namespace hs::mesh
