#pragma once
// Weighted Voronoi stippling's layout for a picture of a given size: the
// grid the dots relax on, how many candidate slots, the spacing and the
// dots' radius. A pure function shared by the renderer
// (render/passes/stipple_passes.h) and its CPU twin in tests, so both
// stipple the same picture the same way.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hs {

struct StippleLayout {
  int gridWidth = 1, gridHeight = 1;  // cells: half the pixels each way, rounded up
  uint32_t candidates = 0;            // slots: one per spacing² cells, at most one per cell
  float spacingCells = 1.5f;          // the dots' spacing where the picture is black, in cells
  float radiusPx = 1.0f;              // the dots' radius, pixels
};

// `spacingPx` and `dotPx` per 1080 rows (the settings' post.stipple.*).
// Under 3 pixels (1.5 cells) a dot's cell is too coarse to relax: the
// spacing stays at that and the radius grows with it, so the picture keeps
// its tone (ink per area pi r² / spacing² where black).
inline StippleLayout stippleLayout(float spacingPx, float dotPx, int width, int height) {
  StippleLayout l;
  l.gridWidth = std::max(1, (width + 1) / 2);
  l.gridHeight = std::max(1, (height + 1) / 2);
  const float lines = float(std::max(height, 1)) / 1080.0f;
  const float asked = std::max(1e-3f, spacingPx * lines);
  const float spacing = std::max(3.0f, asked);
  l.spacingCells = spacing / 2.0f;
  l.radiusPx = std::max(0.05f, dotPx * lines * spacing / asked);
  const double cells = double(l.gridWidth) * double(l.gridHeight);
  l.candidates = uint32_t(std::min(cells, std::ceil(cells / (double(l.spacingCells) * double(l.spacingCells)))));
  return l;
}

}  // namespace hs
