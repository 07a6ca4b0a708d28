#pragma once
// Brush falloff: weight 1 inside (1 - falloff) * radius, then a curve down to
// 0 at the radius (Unreal's "falloff" fraction). Evaluated through a table
// indexed by squared distance, so a dab needs no sqrt per sample.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace hs::terrain {

enum class FalloffShape {
  Smooth,    // smoothstep: soft shoulders (default)
  Linear,    // cone
  Spherical, // dome: sqrt(1 - t^2)
  Tip,       // sharp centre: (1 - t)^2
  Constant,  // hard edge
  Custom,    // piecewise-linear through `points` (t in [0,1] -> weight)
};

struct FalloffCurve {
  FalloffShape shape = FalloffShape::Smooth;
  float falloff = 0.5f;            // fraction of the radius over which the weight falls (0..1)
  std::vector<glm::vec2> points;   // Custom: (t, weight), t from 0 (inner edge) to 1 (radius)

  // Weight at normalised distance r = distance / radius (1 at 0, 0 at >= 1).
  float evaluate(float r) const;
};

// Weight table over r^2 in [0, 1]; weight(r2) for r2 >= 1 is 0.
class FalloffTable {
 public:
  static constexpr int kSize = 1024;
  FalloffTable() = default;
  explicit FalloffTable(const FalloffCurve& c);
  float weight(float r2) const {
    if (r2 >= 1.0f) return 0.0f;
    const float f = r2 * float(kSize);
    const int i = int(f);
    const float t = f - float(i);
    return table_[size_t(i)] + (table_[size_t(i) + 1] - table_[size_t(i)]) * t;
  }

 private:
  std::array<float, kSize + 2> table_{};
};

}  // namespace hs::terrain
