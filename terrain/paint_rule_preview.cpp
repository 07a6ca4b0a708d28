#include "terrain/paint_rule_preview.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {

RulePreview previewRule(const Heightfield& hf, const PaintRule& rule, int maxSize) {
  RulePreview p;
  const int nx = hf.samplesX(), ny = hf.samplesY();
  if (nx < 2 || ny < 2) return p;
  maxSize = std::max(2, maxSize);
  const double scale = std::min(1.0, double(maxSize) / double(std::max(nx, ny)));
  p.width = std::clamp(int(std::lround(nx * scale)), 2, nx);
  p.height = std::clamp(int(std::lround(ny * scale)), 2, ny);
  p.weights.assign(size_t(p.width) * size_t(p.height), 0.0f);
  if (!rule.enabled) return p;
  const float strength = std::clamp(rule.strength, 0.0f, 1.0f);
  size_t some = 0, all = 0;
  for (int v = 0; v < p.height; ++v) {
    const int y = int(std::lround(double(v) * (ny - 1) / (p.height - 1)));
    for (int u = 0; u < p.width; ++u) {
      const int x = int(std::lround(double(u) * (nx - 1) / (p.width - 1)));
      // As applyPaintRules: world altitude and the slope of the central-difference gradient.
      const glm::vec2 g = hf.gradientAt(x, y);
      const double altitude = hf.origin().z + double(hf.at(x, y));
      const double slope = std::atan(std::sqrt(double(g.x * g.x + g.y * g.y))) * 180.0 / M_PI;
      const float w = ruleWeight(rule, altitude, slope);
      p.weights[size_t(v) * size_t(p.width) + size_t(u)] = w;
      some += w > 0.0f;
      all += strength > 0.0f && w >= strength;
    }
  }
  const double n = double(p.weights.size());
  p.coverage = double(some) / n;
  p.full = double(all) / n;
  return p;
}

}  // namespace hs::terrain
