#pragma once
// A prototype decimator on meshoptimizer's schedule, kept to measure one
// design question (docs/meshes.md, "Ninth round"): would passes of
// independent collapses over flat arrays, with our quadrics, optimal
// placement and checks, be faster than our greedy heap at the same
// quality? It is a benchmark's subject, not a product: single-threaded,
// and it leaves out what the bunny does not need (UV seams, materials,
// the polyline error of boundary vertices, locks, regions, progress).
//
// Each pass: vertex-to-face lists of the live faces, every edge evaluated
// once (as CollapseEngine::evaluate does), a radix sort of the keys, then
// the collapses in key order up to meshopt's pass limit (passLimit x the
// key at the position of half the faces still to remove; at least a tenth
// of them), each one's two ends (or whole one-rings) locked for the rest
// of the pass, so that every key taken is still exact when its turn comes.
#include <cstddef>
#include <cstdint>

#include "mesh/mesh_data.h"

namespace hs::bench {

struct PassScheduleOptions {
  double passLimit = 1.5;          // meshopt's 1.5
  bool lockOneRings = false;       // lock the one-rings of both ends, not only the ends
  bool endpointPlacement = false;  // meshopt's placement: the kept vertex never moves
  double lengthWeight = 1e-5;      // as DecimationState::lengthWeight
  double maxNormalDeviationDeg = 60.0, minTriangleQuality = 0.1;  // as DecimateOptions
};

struct PassScheduleStats {
  int passes = 0;
  size_t evaluations = 0, walked = 0, tried = 0, collapses = 0;
  size_t rejectedTopology = 0, rejectedGeometry = 0;
  // Seconds: weld, quadrics and classes; per pass (summed) the face lists,
  // the evaluations, the sort, the collapses.
  double setup = 0, lists = 0, evaluate = 0, sort = 0, collapse = 0;
};

hs::mesh::MeshData decimateInPasses(const hs::mesh::MeshData& in, size_t targetTriangles,
                                    const PassScheduleOptions& options, PassScheduleStats& stats);

}  // namespace hs::bench
