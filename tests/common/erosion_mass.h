#pragma once
// Mass conservation of an erosion run, stated against what the run did:
// the volume it moved, sum |h_after - h_before| * cell area. A tolerance
// relative to the terrain's whole mass (sum |h|) grows with the height the
// terrain sits at and can exceed the material moved; this one does not.
#include <cmath>
#include <cstddef>
#include <vector>

#include "terrain/heightfield.h"

namespace hs::test {

// Mass error / volume moved allowed: what the solvers achieve, with a
// margin. The error is float rounding (heights are floats, each write
// rounds to 7.6e-6 m at 100 m up; the sums are double), so it grows with
// the number of writes, not with the material moved; hence two looser
// bounds for the runs where writes far outnumber what moves. Measured
// (deterministic: the same bits on any thread count), and what a leak of
// 1e-6 of the terrain's mass (sum |h| * cell area) gives instead:
//
//   kErosionMassTolerance 3e-7: runs of up to 1000 iterations. Measured
//     0 .. 3.3e-8 (hydraulic 1000 it on 64^2: 3.3e-8, thermal: 1.6e-8,
//     the scene's thermal job: 2.9e-9); the leak gives 1.6e-6 (thermal on
//     a 100 m cliff, where 50,000 m^3 move) to 1.5e-4. Margins: 9x below,
//     5x above.
//   kLongRunMassTolerance 6e-6: 1e5 iterations on 12x12. Measured 1.9e-6
//     (thermal), 4.3e-8 (hydraulic); the leak gives 2.6e-5. Margins 3x, 4x.
//   kLittleMovedMassTolerance 2e-4: hydraulic erosion of a 100 m cliff,
//     500 iterations over 1600 cells that move 1.2 m^3 in all. Measured
//     4.8e-5; the leak gives 6.5e-2. Margins 4x, 300x.
//
// Checked once by injecting the leak into both solvers (every mass check
// failed), then removing it.
inline constexpr double kErosionMassTolerance = 3e-7;
inline constexpr double kLongRunMassTolerance = 6e-6;
inline constexpr double kLittleMovedMassTolerance = 2e-4;

// One float rounding of every cell, in m^3: sum ulp(h) * cell area. For
// runs that move almost nothing (rain at its 1000 m/s cap drowns the
// hills, so the flow stalls: 0.009 m^3 move on 24x24) a bound relative to
// the volume moved is meaningless and this absolute one is used instead.
// Measured 8.4e-5 m^3 there against 4.4e-3 m^3 allowed (52x margin); the
// 1e-6 leak of the terrain's mass gives 0.06 m^3 (fails by 14x).
inline double oneRoundingPerCell(const std::vector<float>& h, double cellArea) {
  double sum = 0.0;
  for (float x : h) sum += double(std::nextafter(std::abs(x), INFINITY) - std::abs(x));
  return sum * cellArea;
}

inline double movedVolume(const std::vector<float>& before, const std::vector<float>& after, double cellArea) {
  double moved = 0.0;
  for (size_t i = 0; i < before.size() && i < after.size(); ++i)
    moved += std::abs(double(after[i]) - double(before[i]));
  return moved * cellArea;
}

inline double movedVolume(const terrain::Heightfield& before, const terrain::Heightfield& after) {
  double moved = 0.0;
  for (int y = 0; y < before.samplesY(); ++y)
    for (int x = 0; x < before.samplesX(); ++x) moved += std::abs(double(after.at(x, y)) - double(before.at(x, y)));
  return moved * before.spacing().x * before.spacing().y;
}

}  // namespace hs::test
