#pragma once
// Thermal erosion (talus creep): material above the angle of repose slides
// to lower neighbours.
//
// Scheme (per iteration, 8 neighbours): the excess of each downhill
// difference over the talus difference, e_j = (h - h_j) - tan(talus) * dist_j,
// moves a share k * e_j to neighbour j, with
//     k = strength * min(1/8, 0.5 * max_j e_j / sum_j e_j)
// The 0.5 * max / sum part is the classic rule (Musgrave 1989, Olsen 2004:
// move half the largest excess, split in proportion). The 1/8 cap makes the
// update a convex combination, so no sample ever rises above its highest
// neighbour or falls below its lowest: no overshoot, no oscillation,
// unconditionally stable for any talus and strength in range.
// Two passes (compute k per sample; gather h' = h - out + in) read only the
// previous iteration, so the result does not depend on the thread count, and
// every transfer leaves one sample and enters another with the same value:
// mass is conserved up to float rounding, which the report measures.
#include <vector>

#include "core/params.h"
#include "core/progress.h"
#include "terrain/erosion_common.h"

namespace hs::terrain {

class UndoRecorder;

// Ranges, units and help are declared once in thermalParamDecls().
struct ThermalParams {
  double talusDegrees = 35.0;  // angle of repose (90: nothing moves)
  int iterations = 50;
  float strength = 0.5f;       // fraction of the allowed move per iteration
  // Clamps everything to its declared range (NaN -> default) and says what changed.
  ThermalParams sanitized(std::vector<std::string>& warnings) const;
};

// ThermalParams' parameters: talus_deg, iterations, strength (the defaults
// are the struct's). `terrain erode`, the erosion dialog and sanitized()
// all use these.
const std::vector<ParamDecl>& thermalParamDecls();

// Erodes the masked window of `hf`. With a recorder the touched tiles get
// before-copies (one undo step). Cancelling leaves the terrain unchanged.
ErosionReport erodeThermal(Heightfield& hf, const ThermalParams& params, const ErosionMask& mask,
                           UndoRecorder* recorder = nullptr, const Progress* progress = nullptr,
                           int threads = 0);

// The solver on a plain row-major grid (tests, benchmarks). `mask` is
// w*h weights or nullptr for 1 everywhere.
ErosionReport erodeThermalGrid(std::vector<float>& heights, int w, int h, glm::dvec2 spacing,
                               const ThermalParams& params, const float* mask,
                               const Progress* progress = nullptr, int threads = 0);

}  // namespace hs::terrain
