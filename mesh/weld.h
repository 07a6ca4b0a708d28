#pragma once
// Welding of exactly coincident vertices. Exporters split vertices per face
// or per attribute; the processing code needs to know which corners share a
// point (topology) and which also share a texture coordinate (no seam).
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// Maps every vertex to a dense id shared by all vertices with bit-identical
// position (+0.0 and -0.0 count as equal) and, when the spans are not empty,
// identical UV and normal. Ids are given in order of first occurrence, so the
// map is deterministic and keeps the file's vertex order. Returns the number
// of distinct ids in `uniqueCount`. Runs on `threads` workers (0 = all);
// the result does not depend on their number. Vertex counts must stay
// below 2^31.
std::vector<uint32_t> weldMap(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                              std::span<const glm::vec3> normals, uint32_t& uniqueCount, unsigned threads = 0);

// Both welds the decimator needs, from one spatial sort: `posOf` by
// position alone and `wedgeOf` by position + UV (equal to posOf when `uvs`
// is empty). Same ids as weldMap gives (first-occurrence order). Vertices
// are sorted by the Morton code of their position, so exact duplicates sit
// in the same short run and are grouped there; far cheaper at millions of
// vertices than hash tables, whose every probe is a cache miss.
struct PositionWedgeWeld {
  std::vector<uint32_t> posOf, wedgeOf;        // per input vertex: its ids
  std::vector<uint32_t> posFirst, wedgeFirst;  // per id: its first (smallest) input vertex
  uint32_t positionCount = 0, wedgeCount = 0;
};
PositionWedgeWeld weldPositionsAndWedges(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                         unsigned threads = 0);

// Welds exact duplicate vertices of `mesh` in place (position + UV + normal,
// the attributes it has): indices are rewritten, duplicate vertices removed.
// Returns how many vertices were removed.
size_t weldExactDuplicates(MeshData& mesh);

}  // namespace hs::mesh
