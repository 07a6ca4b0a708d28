#include "terrain/brush.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {

const char* toolName(BrushTool t) {
  switch (t) {
    case BrushTool::Raise: return "raise";
    case BrushTool::Lower: return "lower";
    case BrushTool::Smooth: return "smooth";
    case BrushTool::Flatten: return "flatten";
    case BrushTool::Noise: return "noise";
    case BrushTool::Terrace: return "terrace";
    case BrushTool::ThermalErosion: return "thermal erosion";
    case BrushTool::HydraulicErosion: return "hydraulic erosion";
    case BrushTool::Paint: return "paint";
    case BrushTool::Holes: return "holes";
  }
  return "?";
}

BrushSettings BrushSettings::sanitized(const glm::dvec2& gridSpacing, double maxExtent,
                                       std::vector<std::string>& w) const {
  using detail::clampParam;
  BrushSettings s = *this;
  const double minR = 0.5 * std::min(gridSpacing.x, gridSpacing.y);
  s.radius = clampParam(radius, minR, std::max(minR, maxExtent), std::max(minR, 16.0), "brush radius (m)", w);
  const bool metres = tool == BrushTool::Raise || tool == BrushTool::Lower || tool == BrushTool::Noise;
  s.strength = float(clampParam(double(strength), metres ? -1e4 : 0.0, metres ? 1e4 : 1.0, 0.5, "brush strength", w));
  s.spacing = float(clampParam(double(spacing), 0.01, 10.0, 0.25, "brush spacing", w));
  s.falloff.falloff = float(clampParam(double(falloff.falloff), 0.0, 1.0, 0.5, "brush falloff", w));
  s.smoothKernel = int(clampParam(double(smoothKernel), 0.0, 512.0, 0.0, "smooth kernel (samples)", w));
  if (flattenHeight && !std::isfinite(*flattenHeight)) {
    w.push_back("flatten height was not finite; picking it under the brush instead");
    s.flattenHeight.reset();
  }
  s.terrace.stepHeight = float(clampParam(double(terrace.stepHeight), 1e-3, 1e5, 5.0, "terrace step (m)", w));
  s.terrace.offset = float(clampParam(double(terrace.offset), -1e6, 1e6, 0.0, "terrace offset (m)", w));
  s.terrace.sharpness = float(clampParam(double(terrace.sharpness), 0.0, 1.0, 0.7, "terrace sharpness", w));
  s.noise.scale = clampParam(noise.scale, 1e-3, 1e7, 32.0, "noise scale (m)", w);
  s.noise.octaves = int(clampParam(double(noise.octaves), 1.0, 12.0, 4.0, "noise octaves", w));
  s.thermal = thermal.sanitized(w);
  s.hydraulic = hydraulic.sanitized(w);
  s.hydraulicIterationsPerDab = int(clampParam(double(hydraulicIterationsPerDab), 1.0, 10000.0, 20.0, "hydraulic iterations per dab", w));
  return s;
}

}  // namespace hs::terrain
