#pragma once
// Line plots for benchmarks, drawn with QPainter and written as PNG: one or
// more panels side by side, each with linear or log axes (1-2-5 ticks, or
// decades with minor ticks at 2..9), a grid, axis labels, a title, one
// polyline with markers per series (optional dashes and a label beside
// each point) and a legend. Works without a display: it starts its own
// QGuiApplication on the "offscreen" platform when the program has none.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace hs::bench {

struct PlotColour {
  uint8_t r = 0, g = 0, b = 0;
};

enum class PlotMarker { Circle, Square, Triangle, Diamond };

struct PlotSeries {
  std::string name;  // in the legend
  PlotColour colour;
  PlotMarker marker = PlotMarker::Circle;
  bool dashed = false;
  std::vector<std::pair<double, double>> points;  // (x, y), joined in this order
  std::vector<std::string> pointLabels;           // optional, one per point, drawn beside it
};

struct PlotPanel {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;  // a log axis leaves out points <= 0
  std::vector<PlotSeries> series;
};

// Draws `panels` side by side, each `panelWidth` x `height` pixels, into a
// PNG at `path`. Returns "" on success, else what went wrong.
std::string savePlotPng(const std::vector<PlotPanel>& panels, const std::string& path, int panelWidth = 900,
                        int height = 600);

}  // namespace hs::bench
