#pragma once
// Seeded, area-proportional surface sampling. Each face gets its share of
// the samples by area (cumulative rounding, so the total is exact), and the
// k-th sample of face f comes from a counter-based generator keyed by
// (seed, f, k): samples can be produced in any order, by any thread, and are
// the same on every run.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// first[f] .. first[f+1] are face f's samples; first.back() == total.
std::vector<uint64_t> allocateSamples(const MeshData& mesh, uint64_t total);

// Uniformly distributed barycentric coordinates for sample k of face f.
glm::dvec3 sampleBarycentric(uint64_t seed, uint32_t face, uint64_t k);

// Samples 0..out.size() of face f as points, in double, moved by `offset`
// (the error report's, and what its benchmark queries).
void faceSamples(const MeshData& mesh, size_t face, uint64_t seed, const glm::dvec3& offset,
                 std::span<glm::dvec3> out);

// Twice the area of each face, in double (local coordinates).
double faceDoubleArea(const MeshData& mesh, size_t face);

}  // namespace hs::mesh
