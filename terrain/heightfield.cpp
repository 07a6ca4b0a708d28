#include "terrain/heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs::terrain {

// Written with conditionals (not std::min, which GCC 12 does not vectorise)
// under `omp simd` (the library builds with -fopenmp-simd): 4x faster, which
// matters because every dab refreshes the bounds of the tiles it touched.
void minMaxSpan(const float* p, int n, float& lo, float& hi) {
  float l = lo, h = hi;
#pragma omp simd reduction(min : l) reduction(max : h)
  for (int i = 0; i < n; ++i) {
    l = p[i] < l ? p[i] : l;
    h = p[i] > h ? p[i] : h;
  }
  lo = l;
  hi = h;
}

Result<Heightfield> Heightfield::create(const HeightfieldDesc& d) {
  if (d.samplesX < kMinSamples || d.samplesY < kMinSamples || d.samplesX > kMaxSamples ||
      d.samplesY > kMaxSamples)
    return Result<Heightfield>::failure(
        "terrain size " + std::to_string(d.samplesX) + " x " + std::to_string(d.samplesY) +
        " samples is outside 2..8193 per side");
  if (!(std::isfinite(d.sizeMetres.x) && std::isfinite(d.sizeMetres.y) && d.sizeMetres.x > 0.0 &&
        d.sizeMetres.y > 0.0 && d.sizeMetres.x < 1e8 && d.sizeMetres.y < 1e8))
    return Result<Heightfield>::failure("terrain extent must be a positive size below 100,000 km");
  if (!(std::isfinite(d.origin.x) && std::isfinite(d.origin.y) && std::isfinite(d.origin.z)))
    return Result<Heightfield>::failure("terrain origin must be finite");
  if (!std::isfinite(d.initialHeight))
    return Result<Heightfield>::failure("initial height must be finite");
  Heightfield h;
  h.heights_ = TileGrid<float>(d.samplesX, d.samplesY, d.initialHeight, /*dense=*/true);
  h.holes_ = TileGrid<uint8_t>(d.samplesX, d.samplesY, 0, /*dense=*/false);
  h.spacing_ = d.sizeMetres / glm::dvec2(d.samplesX - 1, d.samplesY - 1);
  h.origin_ = d.origin;
  h.geo_ = d.geo;
  h.tileBounds_.assign(size_t(h.heights_.tileCount()), HeightRange{d.initialHeight, d.initialHeight});
  return h;
}

Heightfield Heightfield::clone() const {
  Heightfield h;
  h.heights_ = heights_.clone();
  h.holes_ = holes_.clone();
  h.tileBounds_ = tileBounds_;
  h.spacing_ = spacing_;
  h.origin_ = origin_;
  h.geo_ = geo_;
  return h;
}

HeightfieldDesc Heightfield::desc() const {
  HeightfieldDesc d;
  d.samplesX = samplesX();
  d.samplesY = samplesY();
  d.sizeMetres = sizeMetres();
  d.origin = origin_;
  d.geo = geo_;
  return d;
}

float Heightfield::atClamped(int x, int y) const {
  return heights_.get(std::clamp(x, 0, samplesX() - 1), std::clamp(y, 0, samplesY() - 1));
}

void Heightfield::set(int x, int y, float h) {
  heights_.set(x, y, h);
  // Widen (never shrink) the bounds of every tile whose cells use this
  // sample, so bounds stay conservative; updateBounds() makes them tight.
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int sx = x - dx, sy = y - dy;
      if (sx < 0 || sy < 0) continue;
      if (dx && (x & kTileMask) != 0) continue;  // only the left/bottom neighbour tile shares an edge
      if (dy && (y & kTileMask) != 0) continue;
      auto& b = tileBounds_[size_t(heights_.tileIndex(sx, sy))];
      b.min = std::min(b.min, h);
      b.max = std::max(b.max, h);
    }
}

std::vector<float> Heightfield::read(const Region& r) const {
  std::vector<float> out(r.samples());
  heights_.forEachTile(r, [&](int t, const Region& part) {
    const float* tile = heights_.tile(t);
    for (int y = part.y0; y < part.y1; ++y) {
      float* dst = out.data() + size_t(y - r.y0) * size_t(r.width()) + (part.x0 - r.x0);
      if (tile) {
        const float* src = tile + TileGrid<float>::localIndex(part.x0, y);
        std::copy(src, src + part.width(), dst);
      } else {
        std::fill(dst, dst + part.width(), heights_.fill());
      }
    }
  });
  return out;
}

void Heightfield::write(const Region& r, const std::vector<float>& values) {
  heights_.forEachTile(r, [&](int t, const Region& part) {
    float* tile = heights_.tileForWrite(t);
    for (int y = part.y0; y < part.y1; ++y) {
      const float* src = values.data() + size_t(y - r.y0) * size_t(r.width()) + (part.x0 - r.x0);
      std::copy(src, src + part.width(), tile + TileGrid<float>::localIndex(part.x0, y));
    }
  });
  updateBounds(r);
}

void Heightfield::setHole(int x, int y, bool hole) {
  if (isHole(x, y) == hole) return;
  holes_.set(x, y, hole ? 1 : 0);
  if (!hole) holes_.releaseIfUniform(holes_.tileIndex(x, y));
}

bool Heightfield::cellIsHole(int cx, int cy) const {
  // Fast path: no hole tile allocated under the cell's corners.
  const int x1 = std::min(cx + 1, samplesX() - 1), y1 = std::min(cy + 1, samplesY() - 1);
  return isHole(cx, cy) || isHole(x1, cy) || isHole(cx, y1) || isHole(x1, y1);
}

float Heightfield::heightAtLocal(const glm::dvec2& local) const {
  const double fx = std::clamp(local.x / spacing_.x, 0.0, double(samplesX() - 1));
  const double fy = std::clamp(local.y / spacing_.y, 0.0, double(samplesY() - 1));
  const int x0 = std::min(int(fx), samplesX() - 2), y0 = std::min(int(fy), samplesY() - 2);
  const float tx = float(fx - x0), ty = float(fy - y0);
  const float h00 = at(x0, y0), h10 = at(x0 + 1, y0), h01 = at(x0, y0 + 1), h11 = at(x0 + 1, y0 + 1);
  return (h00 * (1.0f - tx) + h10 * tx) * (1.0f - ty) + (h01 * (1.0f - tx) + h11 * tx) * ty;
}

std::optional<double> Heightfield::surfaceAtWorld(const glm::dvec2& world) const {
  const glm::dvec2 local = worldToLocal(world);
  const glm::dvec2 s = localToSample(local);
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x <= samplesX() - 1 && s.y <= samplesY() - 1)) return std::nullopt;
  const int cx = std::min(int(s.x), samplesX() - 2), cy = std::min(int(s.y), samplesY() - 2);
  if (cellIsHole(cx, cy)) return std::nullopt;
  return origin_.z + double(heightAtLocal(local));
}

glm::vec2 Heightfield::gradientAt(int x, int y) const {
  const int xm = std::max(x - 1, 0), xp = std::min(x + 1, samplesX() - 1);
  const int ym = std::max(y - 1, 0), yp = std::min(y + 1, samplesY() - 1);
  const float gx = (at(xp, y) - at(xm, y)) / float(double(xp - xm) * spacing_.x);
  const float gy = (at(x, yp) - at(x, ym)) / float(double(yp - ym) * spacing_.y);
  return {gx, gy};
}

glm::vec3 Heightfield::normalAtLocal(const glm::dvec2& local) const {
  const double fx = std::clamp(local.x / spacing_.x, 0.0, double(samplesX() - 1));
  const double fy = std::clamp(local.y / spacing_.y, 0.0, double(samplesY() - 1));
  const int x0 = std::min(int(fx), samplesX() - 2), y0 = std::min(int(fy), samplesY() - 2);
  const float tx = float(fx - x0), ty = float(fy - y0);
  const glm::vec2 g = (gradientAt(x0, y0) * (1.0f - tx) + gradientAt(x0 + 1, y0) * tx) * (1.0f - ty) +
                      (gradientAt(x0, y0 + 1) * (1.0f - tx) + gradientAt(x0 + 1, y0 + 1) * tx) * ty;
  return glm::normalize(glm::vec3(-g.x, -g.y, 1.0f));
}

HeightRange Heightfield::tileBounds(int t) const { return tileBounds_[size_t(t)]; }

HeightRange Heightfield::range() const {
  HeightRange r{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
  for (const auto& b : tileBounds_) {
    r.min = std::min(r.min, b.min);
    r.max = std::max(r.max, b.max);
  }
  return r;
}

void Heightfield::updateBounds(const Region& changed) {
  const Region r = changed.intersected(bounds());
  if (r.empty()) return;
  // A tile's cells use samples up to x0+128, so a change at the first column
  // or row of a tile also affects the tile to its left / below.
  const int tx0 = std::max(0, (r.x0 - 1) >> kTileShift), ty0 = std::max(0, (r.y0 - 1) >> kTileShift);
  const int tx1 = (r.x1 - 1) >> kTileShift, ty1 = (r.y1 - 1) >> kTileShift;
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) {
      const int t = heights_.tileIndexOfTile(tx, ty);
      const int x0 = tx * kTileSize, y0 = ty * kTileSize;
      const int x1 = std::min(x0 + kTileSize + 1, samplesX()), y1 = std::min(y0 + kTileSize + 1, samplesY());
      float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
      heights_.forEachTile(Region{x0, y0, x1, y1}, [&](int s, const Region& part) {
        const float* tile = heights_.tile(s);
        if (!tile) {
          lo = std::min(lo, heights_.fill());
          hi = std::max(hi, heights_.fill());
          return;
        }
        for (int y = part.y0; y < part.y1; ++y)
          minMaxSpan(tile + TileGrid<float>::localIndex(part.x0, y), part.width(), lo, hi);
      });
      tileBounds_[size_t(t)] = {lo, hi};
    }
}

void Heightfield::updateAllBounds() { updateBounds(bounds()); }

size_t Heightfield::memoryBytes() const {
  return heights_.memoryBytes() + holes_.memoryBytes() + tileBounds_.size() * sizeof(HeightRange);
}

}  // namespace hs::terrain
