#pragma once
// A half-open rectangle of samples [x0,x1) x [y0,y1). Every edit reports the
// region it changed so the renderer uploads only that and the file saves only
// the tiles under it.
#include <algorithm>
#include <cstddef>

namespace hs::terrain {

struct Region {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return empty() ? 0 : x1 - x0; }
  int height() const { return empty() ? 0 : y1 - y0; }
  size_t samples() const { return size_t(width()) * size_t(height()); }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }

  Region united(const Region& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
  Region intersected(const Region& o) const {
    Region r{std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
    return r.empty() ? Region{} : r;
  }
  Region expanded(int by) const {
    return empty() ? Region{} : Region{x0 - by, y0 - by, x1 + by, y1 + by};
  }
  bool operator==(const Region&) const = default;
};

}  // namespace hs::terrain
