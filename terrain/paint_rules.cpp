#include "terrain/paint_rules.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace hs::terrain {
namespace {

// 1 inside [lo, hi], smoothstep down to 0 over `blend` outside.
double band(double v, double lo, double hi, double blend) {
  if (v >= lo && v <= hi) return 1.0;
  if (blend <= 0.0) return 0.0;
  const double d = v < lo ? lo - v : v - hi;
  if (d >= blend) return 0.0;
  const double t = 1.0 - d / blend;
  return t * t * (3.0 - 2.0 * t);
}

bool finiteRule(const PaintRule& r) {
  for (double v : {r.altitudeMin, r.altitudeMax, r.altitudeBlend, r.slopeMin, r.slopeMax, r.slopeBlend})
    if (!std::isfinite(v)) return false;
  return std::isfinite(r.strength);
}

}  // namespace

float ruleWeight(const PaintRule& r, double altitude, double slope) {
  double w = 1.0;
  if (r.useAltitude) w *= band(altitude, r.altitudeMin, r.altitudeMax, std::max(0.0, r.altitudeBlend));
  if (r.useSlope) w *= band(slope, r.slopeMin, r.slopeMax, std::max(0.0, r.slopeBlend));
  return float(w * std::clamp(double(r.strength), 0.0, 1.0));
}

PaintRulesResult applyPaintRules(Terrain& terrain, const std::vector<PaintRule>& rules, Region region,
                                 const Progress* progress, int threads) {
  PaintRulesResult res;
  const Heightfield& hf = terrain.height;
  PaintLayers& paint = terrain.paint;
  if (region.empty()) region = hf.bounds();
  region = region.intersected(hf.bounds());
  std::vector<PaintRule> active;
  for (size_t i = 0; i < rules.size(); ++i) {
    const PaintRule& r = rules[i];
    if (!r.enabled) continue;
    if (r.layer < 0 || r.layer >= paint.layerCount()) {
      res.warnings.push_back("rule " + std::to_string(i + 1) + " names paint layer " + std::to_string(r.layer) +
                             ", which does not exist; skipped");
      continue;
    }
    if (!finiteRule(r)) {
      res.warnings.push_back("rule " + std::to_string(i + 1) + " has a non-finite value; skipped");
      continue;
    }
    active.push_back(r);
  }
  if (region.empty() || active.empty()) return res;

  // Altitude and slope once per sample, shared by all rules.
  const int w = region.width(), h = region.height();
  std::vector<float> alt(region.samples()), slope(region.samples());
  parallelFor(h, threads, 16, [&](int b, int e) {
    for (int y = region.y0 + b; y < region.y0 + e; ++y)
      for (int x = region.x0; x < region.x1; ++x) {
        const size_t i = size_t(y - region.y0) * size_t(w) + size_t(x - region.x0);
        const glm::vec2 g = hf.gradientAt(x, y);
        alt[i] = float(hf.origin().z + double(hf.at(x, y)));
        slope[i] = float(std::atan(std::sqrt(double(g.x * g.x + g.y * g.y))) * 180.0 / M_PI);
      }
  });

  UndoRecorder rec(terrain);
  rec.recordPaint(region);
  for (size_t ri = 0; ri < active.size(); ++ri) {
    if (isCancelled(progress)) {
      // Put back what earlier rules changed: the edit is all or nothing.
      UndoStep partial = rec.finish("cancelled");
      partial.swap(terrain);
      res.cancelled = true;
      return res;
    }
    const PaintRule& r = active[ri];
    paint.prepareBlend(region, r.layer);
    parallelFor(h, threads, 16, [&](int b, int e) {
      for (int y = region.y0 + b; y < region.y0 + e; ++y)
        for (int x = region.x0; x < region.x1; ++x) {
          const size_t i = size_t(y - region.y0) * size_t(w) + size_t(x - region.x0);
          const float a = ruleWeight(r, double(alt[i]), double(slope[i]));
          if (a > 0.0f) paint.blendPrepared(x, y, r.layer, a);
        }
    });
    reportProgress(progress, double(ri + 1) / double(active.size()), "paint rules");
  }
  paint.releaseUniformTiles(region);
  res.changed = region;
  res.undo = rec.finish("terrain paint rules");
  return res;
}

Result<LayerMask> exportLayerMask(const PaintLayers& paint, int layer, Region region) {
  if (layer < 0 || layer >= paint.layerCount())
    return Result<LayerMask>::failure("no paint layer " + std::to_string(layer));
  const Region all{0, 0, paint.samplesX(), paint.samplesY()};
  region = region.empty() ? all : region.intersected(all);
  LayerMask m;
  m.region = region;
  m.values.resize(region.samples());
  for (int y = region.y0; y < region.y1; ++y)
    for (int x = region.x0; x < region.x1; ++x)
      m.values[size_t(y - region.y0) * size_t(region.width()) + size_t(x - region.x0)] = paint.weight(layer, x, y);
  return m;
}

}  // namespace hs::terrain
