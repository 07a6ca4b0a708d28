// The erosion solvers' parameters, declared once (core/params.h), and the
// clamping every solver run starts with, by the same declarations.
//
// Iterations are 1..1,000,000 everywhere: zero iterations would do nothing
// and still cost the user an undo step; the CLI used to accept 0 while the
// dialog started at 1. Rates are 0..1000 (per second): the dialog's limits,
// already far beyond any useful setting, with the solver's K*dt caps below
// 1 keeping even the extremes stable.
#include <array>

#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"

namespace hs::terrain {

const std::vector<ParamDecl>& thermalParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const ThermalParams d;
    return std::vector<ParamDecl>{
        {.key = "talus_deg", .option = "talus", .label = "Talus angle", .unit = Unit::Degrees, .min = 0.0, .max = 90.0,
         .defaultValue = d.talusDegrees, .help = "angle of repose: steeper slopes creep down (90: nothing moves)",
         .valueName = "DEG", .editor = true, .decimals = 1, .group = "thermal"},
        {.key = "iterations", .option = "iterations", .label = "Iterations", .min = 1, .max = 1000000, .integer = true,
         .defaultValue = d.iterations, .help = "solver iterations", .valueName = "N", .editor = true},
        {.key = "strength", .option = "strength", .label = "Strength", .min = 0.0, .max = 1.0,
         .defaultValue = double(d.strength), .help = "share of the allowed move per iteration", .valueName = "S",
         .editor = true, .decimals = 3, .step = 0.05, .group = "thermal"},
    };
  }();
  return decls;
}

const std::vector<ParamDecl>& hydraulicParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const HydraulicParams d;
    const std::string g = "hydraulic (virtual pipes)";
    return std::vector<ParamDecl>{
        {.key = "iterations", .option = "iterations", .label = "Iterations", .min = 1, .max = 1000000, .integer = true,
         .defaultValue = d.iterations, .help = "solver iterations", .valueName = "N", .editor = true},
        {.key = "time_step_s", .option = "time-step", .label = "Time step (upper bound)", .unit = Unit::Seconds,
         .min = 1e-4, .max = 10.0, .defaultValue = d.timeStep,
         .help = "simulated time per iteration at most (the stability limit may shorten it)", .valueName = "S",
         .editor = true, .decimals = 4, .step = 0.01, .group = g},
        {.key = "rain_m_per_s", .option = "rain", .label = "Rain", .unit = Unit::MetresPerSecond, .min = 0.0,
         .max = 1000.0, .defaultValue = d.rain, .help = "water added per second (times the mask)",
         .valueName = "M_PER_S", .editor = true, .decimals = 4, .step = 0.001, .group = g},
        {.key = "evaporation_per_s", .option = "evaporation", .label = "Evaporation", .unit = Unit::PerSecond,
         .min = 0.0, .max = 1000.0, .defaultValue = d.evaporation, .help = "share of the water evaporating per second",
         .valueName = "PER_S", .editor = true, .decimals = 3, .step = 0.05, .group = g},
        {.key = "sediment_capacity", .option = "capacity", .label = "Sediment capacity", .min = 0.0, .max = 1000.0,
         .defaultValue = d.sedimentCapacity, .help = "Kc: sediment the flow can carry per speed and slope",
         .valueName = "KC", .editor = true, .decimals = 3, .step = 0.1, .group = g},
        {.key = "erosion_rate_per_s", .option = "erosion-rate", .label = "Erosion rate", .unit = Unit::PerSecond,
         .min = 0.0, .max = 1000.0, .defaultValue = d.erosionRate,
         .help = "Ks: how fast water picks up rock below capacity", .valueName = "KS", .editor = true, .decimals = 3,
         .step = 0.05, .group = g},
        {.key = "deposition_rate_per_s", .option = "deposition-rate", .label = "Deposition rate",
         .unit = Unit::PerSecond, .min = 0.0, .max = 1000.0, .defaultValue = d.depositionRate,
         .help = "Kd: how fast sediment settles above capacity", .valueName = "KD", .editor = true, .decimals = 3,
         .step = 0.05, .group = g},
        // The solver's own settings: no option, no widget.
        {.key = "min_slope", .label = "Minimum slope", .min = 0.0, .max = 1.0, .defaultValue = d.minSlope,
         .help = "keeps some capacity on flat ground"},
        {.key = "depth_limit_m", .label = "Depth limit", .unit = Unit::Metres, .min = 1e-6, .max = 1000.0,
         .defaultValue = d.depthLimit, .help = "capacity grows with depth up to this depth"},
        {.key = "gravity", .label = "Gravity", .min = 0.01, .max = 1000.0, .defaultValue = d.gravity,
         .help = "m/s^2"},
        {.key = "cfl", .label = "CFL number", .min = 0.01, .max = 0.9, .defaultValue = d.cfl,
         .help = "Courant number of the time-step limit"},
        {.key = "friction_per_s", .label = "Flow friction", .unit = Unit::PerSecond, .min = 0.0, .max = 10000.0,
         .defaultValue = d.friction, .help = "bed friction"},
    };
  }();
  return decls;
}

ThermalParams ThermalParams::sanitized(std::vector<std::string>& w) const {
  const std::vector<ParamDecl>& d = thermalParamDecls();
  const char* ctx = "thermal erosion";
  ThermalParams p;
  p.talusDegrees = clampParam(paramIn(d, "talus_deg"), talusDegrees, w, ctx);
  p.iterations = int(clampParam(paramIn(d, "iterations"), double(iterations), w, ctx));
  p.strength = float(clampParam(paramIn(d, "strength"), double(strength), w, ctx));
  return p;
}

HydraulicParams HydraulicParams::sanitized(std::vector<std::string>& w) const {
  const std::vector<ParamDecl>& d = hydraulicParamDecls();
  const char* ctx = "hydraulic erosion";
  auto clamp = [&](const char* key, double v) { return clampParam(paramIn(d, key), v, w, ctx); };
  HydraulicParams p;
  p.iterations = int(clamp("iterations", double(iterations)));
  p.timeStep = clamp("time_step_s", timeStep);
  p.rain = clamp("rain_m_per_s", rain);
  p.evaporation = clamp("evaporation_per_s", evaporation);
  p.sedimentCapacity = clamp("sediment_capacity", sedimentCapacity);
  p.erosionRate = clamp("erosion_rate_per_s", erosionRate);
  p.depositionRate = clamp("deposition_rate_per_s", depositionRate);
  p.minSlope = clamp("min_slope", minSlope);
  p.depthLimit = clamp("depth_limit_m", depthLimit);
  p.gravity = clamp("gravity", gravity);
  p.cfl = clamp("cfl", cfl);
  p.friction = clamp("friction_per_s", friction);
  return p;
}

}  // namespace hs::terrain
