#pragma once
// Brush tools and their settings. Sizes are in metres (what the user sees);
// a dab's footprint in samples is radius / spacing. Strength means, per tool:
//   Raise/Lower, Noise: metres added at the centre per dab (times falloff)
//   Smooth, Flatten, Terrace, Paint: blend fraction per dab, 0..1
//   Holes: > 0 cuts holes, erase restores the surface
//   Thermal/Hydraulic: scales the erosion mask
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"
#include "terrain/falloff.h"
#include "terrain/noise.h"

namespace hs::terrain {

enum class BrushTool { Raise, Lower, Smooth, Flatten, Noise, Terrace, ThermalErosion, HydraulicErosion, Paint, Holes };
const char* toolName(BrushTool t);

enum class FlattenMode {
  Height,  // to a picked (or given) height
  Slope,   // to the plane fitted under the brush where the stroke began
};
enum class FlattenDirection { Both, RaiseOnly, LowerOnly };

struct TerraceOptions {
  float stepHeight = 5.0f;  // metres between benches
  float offset = 0.0f;      // height of one bench, metres
  float sharpness = 0.7f;   // share of each step that is flat bench (0: no terrace, 1: hard steps)
};

struct BrushSettings {
  BrushTool tool = BrushTool::Raise;
  double radius = 16.0;    // metres
  float strength = 0.5f;   // see above
  FalloffCurve falloff;
  float spacing = 0.25f;   // distance between dabs as a fraction of the radius (pen spacing)
  bool pressureStrength = true;  // pen pressure scales strength
  bool pressureRadius = false;   // pen pressure scales radius

  // Smooth: box-filter radius in samples (two passes); 0 = radius_in_samples / 10.
  int smoothKernel = 0;
  // Flatten
  FlattenMode flattenMode = FlattenMode::Height;
  FlattenDirection flattenDirection = FlattenDirection::Both;
  std::optional<float> flattenHeight;  // local height; unset = picked under the first dab
  // Noise
  FractalNoise noise;
  // Terrace
  TerraceOptions terrace;
  // Erosion brushes: iterations run per dab.
  ThermalParams thermal{35.0, 8, 0.5f};
  HydraulicParams hydraulic{};
  int hydraulicIterationsPerDab = 20;
  // Paint
  int paintLayer = 0;
  // Paint/Holes: remove instead of add.
  bool erase = false;

  // Clamped copy for the given terrain spacing (NaN -> default), with what changed.
  BrushSettings sanitized(const glm::dvec2& gridSpacing, double maxExtent, std::vector<std::string>& warnings) const;
};

}  // namespace hs::terrain
