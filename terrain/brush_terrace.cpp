// Terrace: blend toward a stepped profile of the heights the stroke started
// from (its before-copies), so dabbing the same place again converges to the
// terrace instead of stepping down further each time.
#include <algorithm>
#include <cmath>

#include "terrain/brush_dab.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

float terraceHeight(float h, const TerraceOptions& o) {
  // Each step: a flat bench over `sharpness` of the step, then a straight
  // riser up to the next bench. Continuous, so no cliffs appear from nothing.
  const double step = double(o.stepHeight);
  const double t = (double(h) - double(o.offset)) / step;
  const double i = std::floor(t), f = t - i;
  const double sh = double(o.sharpness);
  const double g = sh >= 1.0 ? 0.0 : std::max(0.0, (f - sh) / (1.0 - sh));
  return float(double(o.offset) + (i + g) * step);
}

void dabTerrace(const DabContext& ctx, const TerraceOptions& opts) {
  const float s = ctx.strength;
  auto& grid = ctx.hf->heights();
  forEachDabSample(ctx, [&](float& h, int x, int y, float w) {
    const int t = grid.tileIndex(x, y);
    const float* before = ctx.recorder ? ctx.recorder->heightsBefore(t) : nullptr;
    const float orig = before ? before[TileGrid<float>::localIndex(x, y)] : h;
    const float goal = terraceHeight(orig, opts);
    const float a = std::min(1.0f, s * w);
    h = (1.0f - a) * h + a * goal;
  });
}

}  // namespace hs::terrain
