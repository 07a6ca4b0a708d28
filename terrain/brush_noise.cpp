// Noise: adds strength * falloff * fractal noise. The noise is a function of
// the terrain-local position (not of the dab), so overlapping dabs and
// repeated strokes agree, and a seed reproduces the same result anywhere.
#include <vector>

#include "terrain/brush_dab.h"

namespace hs::terrain {

void dabNoise(const DabContext& ctx, const FractalNoise& noise) {
  const Region r = ctx.region;
  const glm::dvec2 sp = ctx.hf->spacing();
  auto& grid = ctx.hf->heights();
  const float s = ctx.strength;
  parallelFor(r.height(), ctx.threads, 32, [&](int b, int e) {
    std::vector<float> row(size_t(r.width()));
    for (int yy = b; yy < e; ++yy) {
      const int y = r.y0 + yy;
      const float dy = float((y - ctx.centre.y) * ctx.invRadius.y);
      if (dy * dy >= 1.0f) continue;
      // Only the span of the row inside the circle needs noise.
      const double half = std::sqrt(1.0 - double(dy) * double(dy)) / ctx.invRadius.x;
      const int xa = std::max(r.x0, int(std::ceil(ctx.centre.x - half)));
      const int xb = std::min(r.x1, int(std::floor(ctx.centre.x + half)) + 1);
      if (xa >= xb) continue;
      noise.row(xa * sp.x, sp.x, y * sp.y, xb - xa, row.data());
      for (int x = xa; x < xb; ++x) {
        const float w = ctx.weight(x, y);
        if (w <= 0.0f) continue;
        float* tile = grid.preparedTile(grid.tileIndex(x, y));
        tile[TileGrid<float>::localIndex(x, y)] += s * w * row[size_t(x - xa)];
      }
    }
  });
}

}  // namespace hs::terrain
