#pragma once
// Non-manifold topology: edges shared by three or more faces (or by two faces
// running the same direction) and vertices whose faces form more than one
// fan (bow-ties). A half-edge structure such as OpenMesh cannot hold either,
// so they are split by duplicating vertices; no face is ever removed.
//
// Everything here works on a triangle list over abstract vertex ids, so the
// same code serves the cleaner (ids = mesh vertices) and the decimator (ids =
// welded positions, where UV seams do not cut the topology).
#include <cstdint>
#include <span>
#include <vector>

#include "core/uninit_array.h"

namespace hs::mesh {

constexpr uint32_t kNoCorner = UINT32_MAX;

// Corner c of a triangle list is the directed edge tris[c] -> tris[next(c)],
// next(c) = c - c % 3 + (c + 1) % 3.
inline uint32_t nextCorner(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
inline uint32_t prevCorner(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

struct CornerTopology {
  // Per corner: the corner of the opposite directed edge in the neighbouring
  // face; kNoCorner on open boundaries and on non-manifold edges.
  UninitArray<uint32_t> twin;  // every element written (huge pages at scale)
  size_t nonManifoldEdges = 0;     // undirected edges with 3+ faces or a repeated direction
  size_t nonManifoldVertices = 0;  // vertices whose faces form 2+ fans (non-manifold edges count as cuts)
  size_t boundaryEdges = 0;        // edges with one face
  bool manifold() const { return nonManifoldEdges == 0 && nonManifoldVertices == 0; }
};

// Twins and non-manifold counts. Faces must not repeat an id (degenerate
// faces are the cleaner's to remove first); such faces are ignored here.
CornerTopology analyzeCorners(std::span<const uint32_t> tris, uint32_t vertexCount, unsigned threads = 1);

struct NonManifoldSplitStats {
  size_t nonManifoldEdges = 0;     // found before splitting
  size_t nonManifoldVertices = 0;  // bow-tie vertices found before splitting
  size_t verticesAdded = 0;        // duplicates created
  size_t facesDetached = 0;        // faces given their own vertices (last resort, see .cpp)
  size_t wholeMeshAnalyses = 0;    // 1 when the mesh was manifold or one split made it so
};

// Makes `tris` edge- and vertex-manifold and consistently paired by giving
// each fan of a split vertex its own id. New ids start at `vertexCount`;
// copiedFrom[id - vertexCount] is the original id each duplicate copies.
// A split vertex keeps its id for the fan of its first corner (in corner
// order); vertices away from the defects keep theirs, and their corners
// are not rewritten. The work beyond one analysis of the whole mesh is in
// the size of the defects' fans, not of the mesh, unless a defect needs
// more than one round (a face hanging on both ends of its edge, a face
// that repeats an id): each further round analyses the whole mesh.
// On return `topology` describes the (now manifold) result, so callers that
// need twins do not analyse twice.
NonManifoldSplitStats splitNonManifold(std::span<uint32_t> tris, uint32_t vertexCount,
                                       std::vector<uint32_t>& copiedFrom, CornerTopology& topology,
                                       unsigned threads = 1);

}  // namespace hs::mesh
