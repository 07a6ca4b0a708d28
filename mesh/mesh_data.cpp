#include "mesh/mesh_data.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/content_hash.h"
#include "core/large_pages.h"
#include "core/parallel.h"
#include "core/uninit_array.h"

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

void computeVertexNormals(MeshData& mesh, unsigned threads) {
  // The sums in face order (one pass, the same bits for any thread count);
  // the arrays around it on huge pages and filled in parallel: at millions
  // of vertices their first touch cost more than the sums (about 15 us a
  // 4 KiB page on this project's machines, core/large_pages.h).
  const size_t nv = mesh.positions.size();
  UninitArray<glm::dvec3> acc(nv);
  parallelFill(acc.begin(), nv, glm::dvec3(0.0), threads);
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
    // The un-normalised cross product weights each face by its area.
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
    acc[a] += n;
    acc[b] += n;
    acc[c] += n;
  }
  resizeOnHugePages(mesh.normals, nv, threads);
  parallelRanges(nv, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t i = b; i < e; ++i) {
      const double len = glm::length(acc[i]);
      mesh.normals[i] = len > 0.0 ? glm::vec3(acc[i] / len) : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  });
}

std::vector<int> faceMaterials(const MeshData& mesh) {
  std::vector<int> mat(mesh.triangleCount(), -1);
  for (const Submesh& s : mesh.submeshes)
    for (size_t f = s.firstIndex / 3; f < std::min(mesh.triangleCount(), size_t(s.firstIndex + s.indexCount) / 3); ++f)
      mat[f] = s.material;
  return mat;
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

uint64_t contentHash(const MeshData& mesh) {
  ContentHasher f;
  f.value(mesh.origin);
  f.array(mesh.positions).array(mesh.normals).array(mesh.uvs).array(mesh.indices);
  f.value(uint64_t(mesh.submeshes.size()));
  for (const auto& s : mesh.submeshes) f.value(s.firstIndex).value(s.indexCount).value(s.material);
  f.value(uint64_t(mesh.materials.size()));
  for (const auto& m : mesh.materials) f.text(m.name).value(m.baseColor).value(m.diffuseTexture);
  f.value(uint64_t(mesh.textures.size()));
  for (const auto& t : mesh.textures) {
    f.text(t.name).array(t.encoded).value(t.width).value(t.height);
    if (t.encoded.empty()) f.array(t.rgba);
  }
  return f.digest();
}

}  // namespace hs::mesh
