#include "terrain/brush_dab.h"

#include <algorithm>

namespace hs::terrain {

Region dabRegion(const Heightfield& hf, const glm::dvec2& c, double radius) {
  const glm::dvec2 sp = hf.spacing();
  const glm::dvec2 cs = c / sp, rs = glm::dvec2(radius) / sp;
  if (!std::isfinite(cs.x) || !std::isfinite(cs.y) || !(rs.x > 0.0)) return {};
  // Clamp before converting: a centre far off the terrain must not overflow int.
  const double lim = 4.0 * kMaxSamples;
  auto cl = [&](double v) { return std::clamp(v, -lim, lim); };
  // Strictly inside the radius: samples at exactly the radius have weight 0.
  const Region r{int(std::floor(cl(cs.x - rs.x))) + 1, int(std::floor(cl(cs.y - rs.y))) + 1,
                 int(std::ceil(cl(cs.x + rs.x))), int(std::ceil(cl(cs.y + rs.y)))};
  return r.intersected(hf.bounds());
}

}  // namespace hs::terrain
