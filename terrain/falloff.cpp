#include "terrain/falloff.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {

float FalloffCurve::evaluate(float r) const {
  if (!(r < 1.0f)) return 0.0f;  // also NaN
  r = std::max(r, 0.0f);
  const float f = std::isfinite(falloff) ? std::clamp(falloff, 0.0f, 1.0f) : 0.5f;
  const float inner = 1.0f - f;
  if (r <= inner || f <= 0.0f) return 1.0f;
  const float t = (r - inner) / f;  // 0 at the inner edge, 1 at the radius
  switch (shape) {
    case FalloffShape::Linear: return 1.0f - t;
    case FalloffShape::Spherical: return std::sqrt(std::max(0.0f, 1.0f - t * t));
    case FalloffShape::Tip: return (1.0f - t) * (1.0f - t);
    case FalloffShape::Constant: return 1.0f;
    case FalloffShape::Custom: {
      if (points.empty()) return 1.0f - t;
      if (t <= points.front().x) return std::clamp(points.front().y, 0.0f, 1.0f);
      for (size_t i = 1; i < points.size(); ++i)
        if (t <= points[i].x) {
          const glm::vec2 a = points[i - 1], b = points[i];
          const float u = b.x > a.x ? (t - a.x) / (b.x - a.x) : 1.0f;
          return std::clamp(a.y + (b.y - a.y) * u, 0.0f, 1.0f);
        }
      return std::clamp(points.back().y, 0.0f, 1.0f);
    }
    case FalloffShape::Smooth:
    default: {
      const float s = 1.0f - t;
      return s * s * (3.0f - 2.0f * s);
    }
  }
}

FalloffTable::FalloffTable(const FalloffCurve& c) {
  for (int i = 0; i <= kSize; ++i) table_[size_t(i)] = c.evaluate(std::sqrt(float(i) / float(kSize)));
  table_[kSize] = c.shape == FalloffShape::Constant ? table_[kSize - 1] : 0.0f;
  table_[kSize + 1] = table_[kSize];
}

}  // namespace hs::terrain
