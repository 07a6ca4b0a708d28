#include "terrain/minmax_tree.h"

#include <algorithm>
#include <limits>

namespace hs::terrain {

MinMaxTree::MinMaxTree(const Heightfield& hf, int leafCells) {
  leafCells_ = std::clamp(leafCells, 2, 1024);
  const int cellsX = hf.samplesX() - 1, cellsY = hf.samplesY() - 1;
  int nx = (cellsX + leafCells_ - 1) / leafCells_, ny = (cellsY + leafCells_ - 1) / leafCells_;
  while (true) {
    Level l;
    l.nx = std::max(nx, 1);
    l.ny = std::max(ny, 1);
    l.nodes.resize(size_t(l.nx) * size_t(l.ny));
    levels_.push_back(std::move(l));
    if (nx <= 1 && ny <= 1) break;
    nx = (nx + 1) / 2;
    ny = (ny + 1) / 2;
  }
  update(hf, hf.bounds());
}

HeightRange MinMaxTree::leafBounds(const Heightfield& hf, int nx, int ny) const {
  const int x0 = nx * leafCells_, y0 = ny * leafCells_;
  const int x1 = std::min(x0 + leafCells_ + 1, hf.samplesX()), y1 = std::min(y0 + leafCells_ + 1, hf.samplesY());
  HeightRange r{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
  const auto& g = hf.heights();
  g.forEachTile(Region{x0, y0, x1, y1}, [&](int t, const Region& part) {
    const float* tile = g.tile(t);
    if (!tile) {
      r.min = std::min(r.min, g.fill());
      r.max = std::max(r.max, g.fill());
      return;
    }
    for (int y = part.y0; y < part.y1; ++y)
      minMaxSpan(tile + TileGrid<float>::localIndex(part.x0, y), part.width(), r.min, r.max);
  });
  return r;
}

size_t MinMaxTree::update(const Heightfield& hf, const Region& changed) {
  const Region r = changed.intersected(hf.bounds());
  if (r.empty() || levels_.empty()) return 0;
  // Leaves whose cells (x0..x0+leaf inclusive) contain a changed sample.
  int lx0 = std::max(0, (r.x0 - 1) / leafCells_), ly0 = std::max(0, (r.y0 - 1) / leafCells_);
  int lx1 = std::min(levels_[0].nx - 1, (r.x1 - 1) / leafCells_);
  int ly1 = std::min(levels_[0].ny - 1, (r.y1 - 1) / leafCells_);
  size_t count = 0;
  for (int y = ly0; y <= ly1; ++y)
    for (int x = lx0; x <= lx1; ++x) {
      levels_[0].nodes[size_t(y) * size_t(levels_[0].nx) + size_t(x)] = leafBounds(hf, x, y);
      ++count;
    }
  for (size_t lv = 1; lv < levels_.size(); ++lv) {
    lx0 /= 2; ly0 /= 2; lx1 /= 2; ly1 /= 2;
    const Level& below = levels_[lv - 1];
    Level& l = levels_[lv];
    for (int y = ly0; y <= ly1; ++y)
      for (int x = lx0; x <= lx1; ++x) {
        HeightRange b{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
        for (int cy = 2 * y; cy <= std::min(2 * y + 1, below.ny - 1); ++cy)
          for (int cx = 2 * x; cx <= std::min(2 * x + 1, below.nx - 1); ++cx) {
            const HeightRange& c = below.nodes[size_t(cy) * size_t(below.nx) + size_t(cx)];
            b.min = std::min(b.min, c.min);
            b.max = std::max(b.max, c.max);
          }
        l.nodes[size_t(y) * size_t(l.nx) + size_t(x)] = b;
        ++count;
      }
  }
  return count;
}

}  // namespace hs::terrain
