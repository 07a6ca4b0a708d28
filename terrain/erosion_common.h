#pragma once
// What every erosion solver shares: the mask that says where it works, the
// report it returns (mass error, time step limits, what was clamped), and the
// window plumbing (read heights, sanitise, write back with undo).
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/params.h"
#include "terrain/falloff.h"
#include "terrain/heightfield.h"
#include "terrain/paint_layers.h"
#include "terrain/region.h"

namespace hs::terrain {

class UndoRecorder;

// Where erosion acts, with a weight in [0,1] per sample of `region`
// (empty weights = 1 everywhere in the region). Samples outside the region
// never change.
struct ErosionMask {
  Region region;
  std::vector<float> weights;

  float at(int x, int y) const {
    return weights.empty() ? 1.0f : weights[size_t(y - region.y0) * size_t(region.width()) + size_t(x - region.x0)];
  }
  static ErosionMask whole(const Heightfield& hf);
  // The part of this mask inside `r` (weights re-sliced).
  ErosionMask clipped(const Region& r) const;
  // A brush footprint: the falloff of `curve` over a circle (local metres).
  static ErosionMask circle(const Heightfield& hf, const glm::dvec2& centreLocal, double radius,
                            const FalloffCurve& curve);
  // The weights of a paint layer (e.g. erode only where "Scree" is painted);
  // an empty region means the whole terrain.
  static ErosionMask fromPaintLayer(const PaintLayers& paint, int layer, const Region& region = {});
};

struct ErosionReport {
  int iterationsRequested = 0;
  int iterationsDone = 0;
  bool cancelled = false;          // nothing was written
  int threads = 1;
  // Rock + suspended sediment, m^3, over the window, before and after. The
  // difference is floating-point rounding only; the solvers move material,
  // they never create or destroy it.
  double massBefore = 0.0, massAfter = 0.0;
  double massError = 0.0;          // |after - before|, m^3
  double relativeMassError = 0.0;  // massError / sum |height| * cell area
  // Time stepping (hydraulic): what the user asked, what stability allowed.
  double requestedTime = 0.0, simulatedTime = 0.0;
  double minDt = 0.0, maxDt = 0.0;
  int cflLimitedIterations = 0;    // iterations whose step the CFL limit shortened
  size_t nonFiniteHeightsFixed = 0;
  std::vector<std::string> warnings;  // parameters clamped, NaN inputs replaced, ...
  double seconds = 0.0;
  double cellIterationsPerSecond = 0.0;
  Region changed;
};

namespace detail {
// Replaces NaN/Inf heights by the mean of finite 4-neighbours (0 if none);
// returns how many were replaced.
size_t sanitizeHeights(std::vector<float>& h, int w, int hgt);
// Sum of h over the grid in double, row by row in order (deterministic).
double sumHeights(const std::vector<float>& h, int w, int hgt);
// Clamps a double parameter to [lo, hi], replacing NaN by `fallback`, and
// notes the change in `warnings` (hs::clampParam, for settings whose range
// is known only at the call: brushes and ramps).
double clampParam(double v, double lo, double hi, double fallback, const char* name,
                  std::vector<std::string>& warnings);
// What both solvers do around their grid run: clip the mask to the
// terrain, copy its window out, run `solve(heights, width, height,
// weights or nullptr)` on the copy, and unless cancelled write the window
// back through `recorder` (before-copies for undo). A window under 2x2
// samples is refused with a warning.
// The end of a grid run: mass after, its error (absolute and relative to
// the mass the solver started with, `absSum` = sum of |h| then), the run
// time since `start` and the throughput in cell-iterations per second.
void finishReport(ErosionReport& rep, const std::vector<float>& h, int w, int hgt, double cellArea, double absSum,
                  std::chrono::steady_clock::time_point start);
using GridSolver = std::function<ErosionReport(std::vector<float>& heights, int width, int height, const float* weights)>;
ErosionReport erodeWindow(Heightfield& hf, const ErosionMask& mask, UndoRecorder* recorder, const GridSolver& solve);
}  // namespace detail

}  // namespace hs::terrain
