#include "meshproc/surface_sampling.h"

#include <cmath>

namespace hs::mesh {
namespace {

// SplitMix64: a good 64-bit mix, cheap enough to call per sample.
inline uint64_t splitmix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline double unit(uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

}  // namespace

double faceDoubleArea(const MeshData& mesh, size_t f) {
  const glm::dvec3 a(mesh.positions[mesh.indices[f * 3]]), b(mesh.positions[mesh.indices[f * 3 + 1]]),
      c(mesh.positions[mesh.indices[f * 3 + 2]]);
  return glm::length(glm::cross(b - a, c - a));
}

std::vector<uint64_t> allocateSamples(const MeshData& mesh, uint64_t total) {
  const size_t nf = mesh.triangleCount();
  std::vector<double> cum(nf + 1, 0.0);
  for (size_t f = 0; f < nf; ++f) cum[f + 1] = cum[f] + faceDoubleArea(mesh, f);
  std::vector<uint64_t> first(nf + 1, 0);
  const double area = cum[nf];
  for (size_t f = 0; f <= nf; ++f)
    first[f] = area > 0 ? std::min<uint64_t>(total, uint64_t(std::floor(double(total) * (cum[f] / area)))) : 0;
  if (area > 0) first[nf] = total;
  return first;
}

void faceSamples(const MeshData& mesh, size_t face, uint64_t seed, const glm::dvec3& offset,
                 std::span<glm::dvec3> out) {
  auto corner = [&](size_t k) { return glm::dvec3(mesh.positions[mesh.indices[face * 3 + k]]) + offset; };
  const glm::dvec3 a = corner(0), b = corner(1), c = corner(2);
  for (size_t k = 0; k < out.size(); ++k) {
    const glm::dvec3 bc = sampleBarycentric(seed, uint32_t(face), k);
    out[k] = bc.x * a + bc.y * b + bc.z * c;
  }
}

glm::dvec3 sampleBarycentric(uint64_t seed, uint32_t face, uint64_t k) {
  const uint64_t h = splitmix(splitmix(seed ^ (uint64_t(face) << 20)) ^ k);
  const double r1 = unit(h), r2 = unit(splitmix(h));
  // sqrt warps r1 so the density is uniform over the triangle's area.
  const double s = std::sqrt(r1);
  return {1.0 - s, s * (1.0 - r2), s * r2};
}

}  // namespace hs::mesh
