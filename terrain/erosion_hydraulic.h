#pragma once
// Hydraulic erosion with the virtual-pipe shallow-water model (Mei, Decaudin
// & Hu 2007), chosen over droplets because:
//  - it is a grid of per-cell updates, each reading only the previous state,
//    so it runs on any number of threads with bitwise identical results
//    (droplets collide on shared cells: either locks and a result that
//    depends on scheduling, or one thread);
//  - it has a real time step, which we can bound (CFL) so it cannot blow up,
//    and whose error we can measure (bench: result vs 16x smaller steps);
//  - it maps directly to a compute shader later.
// Changes from the paper, each for stability or conservation:
//  - sediment moves with the water through the same pipes (upwind flux form:
//    a pipe that carries fraction phi of a cell's water carries fraction phi
//    of its sediment) instead of semi-Lagrangian advection, which neither
//    conserves mass nor stays positive. Rock + sediment is conserved to float
//    rounding; the report gives the error.
//  - dt is limited every iteration by a CFL bound,
//    dt <= cfl * min(spacing) / (max|v| + sqrt(g * max depth)), and the
//    erosion/deposition/evaporation factors K*dt are capped below 1, so no
//    setting overshoots. The report says how often the limit applied.
//  - capacity tapers to zero in very shallow water (depthLimit), and the flow
//    speed uses a depth of at least depthLimit and is capped at Froude 2
//    (the frictionless pipes let thin sheets slosh at absurd speeds that
//    friction never allows); this removes the singular velocity of the paper
//    at d -> 0 and keeps the CFL step from collapsing.
//  - boundaries are closed walls: water and sediment stay in the window
//    (rain leaves only by evaporation), so nothing is lost at the edges.
// At the end, sediment still suspended is deposited where it is.
#include <cstdint>
#include <vector>

#include "core/params.h"
#include "core/progress.h"
#include "terrain/erosion_common.h"

namespace hs::terrain {

class UndoRecorder;

// Ranges, units and help are declared once in hydraulicParamDecls().
struct HydraulicParams {
  int iterations = 300;
  double timeStep = 0.02;         // s, upper bound; the CFL limit may shorten it
  double rain = 0.01;             // m of water per second (times the mask)
  double evaporation = 0.5;       // 1/s (fraction of water per second)
  double sedimentCapacity = 1.0;  // Kc: capacity = Kc * |v| * max(sin(slope), minSlope) * taper(depth)
  double erosionRate = 0.3;       // Ks, 1/s: how fast water picks up rock below capacity
  double depositionRate = 0.3;    // Kd, 1/s: how fast sediment settles above capacity
  double minSlope = 0.05;         // keeps some capacity on flat ground
  double depthLimit = 0.01;       // m: capacity grows with depth up to this depth
  double gravity = 9.81;          // m/s^2
  double cfl = 0.25;              // Courant number of the time-step limit
  double friction = 2.0;          // 1/s: bed friction; sheet flow on slope S runs at about g * S / friction
  // Clamps everything to its declared range (NaN -> default) and says what changed.
  HydraulicParams sanitized(std::vector<std::string>& warnings) const;
};

// HydraulicParams' parameters (the defaults are the struct's). Those with
// a CLI option (iterations, time-step, rain, evaporation, capacity,
// erosion-rate, deposition-rate) are what `terrain erode` and the erosion
// dialog offer; the rest (min_slope, depth_limit_m, gravity, cfl,
// friction) are the solver's own, declared for sanitized() and reports.
const std::vector<ParamDecl>& hydraulicParamDecls();

ErosionReport erodeHydraulic(Heightfield& hf, const HydraulicParams& params, const ErosionMask& mask,
                             UndoRecorder* recorder = nullptr, const Progress* progress = nullptr,
                             int threads = 0);

// The solver on a plain row-major grid (tests, benchmarks). `mask` is w*h
// weights (rain and erosion are multiplied by it) or nullptr for 1.
// `waterOut`, if set, receives the final water depth.
ErosionReport erodeHydraulicGrid(std::vector<float>& heights, int w, int h, glm::dvec2 spacing,
                                 const HydraulicParams& params, const float* mask,
                                 const Progress* progress = nullptr, int threads = 0,
                                 std::vector<float>* waterOut = nullptr);

}  // namespace hs::terrain
