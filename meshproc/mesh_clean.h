#pragma once
// Cleaning with a report: what photogrammetry exports need before they can
// be decimated (and what a user should know about them). Nothing is dropped
// silently: every removed, quarantined, welded or split item is counted, and
// the first of each kind are listed by their index in the input.
//
// Steps, in order:
//   1. quarantine vertices with NaN/Inf coordinates and faces that use them
//      or refer past the end of the vertex list (removed, indices kept);
//   2. weld exact duplicate vertices (same position, UV and normal bits);
//   3. remove faces that repeat a vertex, have zero area (height below
//      1e-12 of their longest edge) or repeat another face exactly;
//   4. split non-manifold edges (3+ faces, or two faces running the same
//      way) and bow-tie vertices by duplicating vertices, so a half-edge
//      structure (OpenMesh) can hold the mesh; no face is removed for this;
//   5. drop vertices no face uses.
#include <cstdint>
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"

namespace hs::mesh {

struct CleanOptions {
  bool weldDuplicates = true;
  bool removeDuplicateFaces = true;
  bool splitNonManifold = true;
  double zeroAreaTolerance = 1e-12;  // face height / longest edge below this is "zero area"
  unsigned threads = 0;
};

struct CleanReport {
  size_t verticesIn = 0, trianglesIn = 0;
  size_t verticesOut = 0, trianglesOut = 0;
  size_t nonFiniteVertices = 0;        // quarantined
  size_t facesOnNonFiniteVertices = 0; // quarantined with them
  size_t outOfRangeFaces = 0;          // quarantined
  size_t duplicateVerticesWelded = 0;
  size_t repeatedIndexFaces = 0;       // removed
  size_t zeroAreaFaces = 0;            // removed
  size_t duplicateFaces = 0;           // removed
  size_t nonManifoldEdges = 0;         // split
  size_t nonManifoldVertices = 0;      // bow-ties, split
  size_t verticesAddedBySplit = 0;
  size_t facesDetached = 0;            // faces given their own corners (a fin on a fold)
  size_t unusedVerticesRemoved = 0;
  // First input indices of each quarantined/removed kind (at most 100 each),
  // so a message can point at the place in the file.
  std::vector<uint32_t> nonFiniteVertexIndices, outOfRangeFaceIndices, degenerateFaceIndices;
  std::vector<std::string> warnings;   // one per kind that occurred, plain words
  double seconds = 0;
};

// Cleans `mesh` in place. Returns false with `error` set if nothing usable
// is left (no faces, or every face invalid or degenerate); the report still
// says why.
bool cleanMesh(MeshData& mesh, const CleanOptions& options, CleanReport& report, std::string& error,
               const Progress* progress = nullptr);

}  // namespace hs::mesh
