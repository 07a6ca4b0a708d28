#pragma once
// Minimax refinement of a decimated mesh: moves the result's free vertices
// along their normals so that the largest distance between the two surfaces
// around them shrinks.
//
// Why: the decimator places a merged vertex where the sum of squared
// distances to its planes is least (quadric error), a least-squares fit.
// The error report and the users' tools judge the largest distance (the
// Hausdorff), and on scan noise the least-squares place is not where the
// largest one is least: one noise peak, or a valley the new face spans,
// stands out by the whole noise amplitude. Moving the vertex to the centre
// of its distances' range (the Chebyshev centre, along its normal) lowers
// that maximum. Measured (docs/meshes.md, "Minimax refinement"): the
// Hausdorff falls 7-36% on the bunny, the quad scans and a 5M-triangle
// scan tile at 50-1%, the mean moves by -4% to +5%, for a fraction of a
// measurement's time.
//
// What moves: only vertices whose neighbourhood is near the largest
// distance (their local maximum at least `candidateShare` of the mesh's,
// and `moveShare` of it when they move), that are interior and manifold
// (a closed fan of faces of one material: boundary and seam vertices stay
// on their input polylines, as the decimator guarantees), whose position
// no other vertex shares, and not locked. A move is along the vertex
// normal, at most `maxMoveEdgeShare` of its shortest edge, and refused
// where a face around it would turn by more than `maxNormalTurnDeg` or
// come to face against the original surface (the error report's flip
// test, the same arithmetic on the corners as they will be stored: no
// new flipped faces). UVs
// stay: a move along the normal keeps the surface point under the
// texture.
//
// How: the distances are sampled as the error report samples them. Each
// vertex of the original is a sample of the original -> result direction
// (the distance to one triangle is convex, so over an original face it is
// largest at a corner), and (L+1)(L+2)/2 barycentric grid points of each
// result face sample the other way. A sample's distance after a move d of
// vertex v (weight b at the sample, unit normal n) is taken as
// |e - b d n|, e the vector from the surface point to the other surface,
// an upper bound while the other surface's nearest point stays where it
// was; the largest over the vertex's samples is convex in d and minimised
// by ternary search; of the moves within `leastSquaresSlack` of that
// least maximum, the one nearest the least-squares move is taken (the
// largest distance stays about where the minimax puts it, the others pay
// less for it). A candidate's faces are sampled that densely only
// once the screening (each original vertex's nearest face; each result
// vertex and edge midpoint) puts it near the gate. All candidates move at
// once from the same positions (Jacobi), by `damping` of their optimum
// since neighbours move together, for `iterations` rounds. Deterministic: every candidate reads the
// positions of the round before and writes only itself.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"

namespace hs::mesh {

class ErrorMeter;

struct RefineOptions {
  int iterations = 3;
  double damping = 0.7;
  double candidateShare = 0.5;  // vertices looked at: local maximum >= this share of the largest
  double moveShare = 0.7;       // vertices moved: local maximum >= this share of the largest, each round
  // Of the moves within this share of the minimax move's largest distance,
  // the one nearest the least-squares move: about the same maximum, and
  // the mean pays less for it (bunny and quad scans, 50% to 1%: the mean's
  // rise halved, the Hausdorff within a few per cent either way).
  double leastSquaresSlack = 0.02;
  int sampleLevel = 3;          // result -> original: (L+1)(L+2)/2 samples a face (10)
  double maxMoveEdgeShare = 0.25;
  double maxNormalTurnDeg = 30.0;
  // No face that faced along the original surface may come to face
  // against it (the error report's flip test). Off only to show in a test
  // what it prevents.
  bool keepFacingOriginal = true;
  // One per original vertex (the decimator's lockedVertices): result
  // vertices at a locked vertex's position stay.
  std::vector<uint8_t> lockedOriginalVertices;
  unsigned threads = 0;
};

struct RefineReport {
  size_t candidates = 0;  // vertices whose neighbourhood was refined
  size_t moved = 0;       // of them, those that moved
  int iterations = 0;     // rounds run (fewer when a round moved nothing)
  // The largest sampled distance, metres, before and after, over the
  // candidates' samples and the others' screening (a look at the same
  // samples the error report draws more of: the report's Hausdorff is the
  // measure of record).
  double largestBefore = 0, largestAfter = 0;
  double seconds = 0;
  bool cancelled = false;
};

// Refines `result` (a decimation of the meter's original) in place.
// Normals of the moved vertices' faces are recomputed.
RefineReport refineMaxError(const ErrorMeter& meter, MeshData& result, const RefineOptions& options = {},
                            const Progress* progress = nullptr);

}  // namespace hs::mesh
