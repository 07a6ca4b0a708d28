#pragma once
// A tiny log-log line plot rasterizer for benchmarks (there is no plotting
// package on the build machines): axes with decade ticks, labelled with a
// built-in 5x7 font, one polyline with markers per series, a legend, written
// as PNG through OpenImageIO.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::bench {

struct Series {
  std::string name;
  glm::vec3 colour{0.0f};
  std::vector<glm::dvec2> points;  // (x, y), both > 0
};

struct PlotSpec {
  std::string title, xLabel, yLabel;
  int width = 900, height = 560;
  bool logX = true, logY = true;
};

// Returns an empty string on success, else the error.
std::string drawPlot(const PlotSpec& spec, const std::vector<Series>& series, const std::string& path);

}  // namespace hs::bench
