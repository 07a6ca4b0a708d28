#include "terrain/stroke.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {

Stroke::Stroke(Terrain& terrain, const BrushSettings& settings, int threads)
    : terrain_(terrain), recorder_(terrain), threads_(threads) {
  const glm::dvec2 ext = terrain.height.sizeMetres();
  settings_ = settings.sanitized(terrain.height.spacing(), std::max(ext.x, ext.y), warnings_);
  falloff_ = FalloffTable(settings_.falloff);
}

size_t Stroke::bytesFor(const Region& r) const {
  switch (settings_.tool) {
    case BrushTool::Paint: return r.samples() * size_t(terrain_.paint.layerCount()) * sizeof(uint16_t);
    case BrushTool::Holes: return r.samples();
    default: return r.samples() * sizeof(float);
  }
}

StrokeUpdate Stroke::dabAt(const glm::dvec2& local, float pressure) {
  StrokeUpdate u;
  if (finished_) return u;
  double massError = 0.0;
  u.changed = applyDab(local, pressure, &massError);
  u.dabs = 1;
  u.changedBytes = bytesFor(u.changed);
  u.erosionMassError = massError;
  if (!started_) {
    started_ = true;
    carried_ = 0.0;
  }
  last_ = local;
  lastPressure_ = pressure;
  return u;
}

StrokeUpdate Stroke::moveTo(const glm::dvec2& local, float pressure) {
  if (finished_ || !std::isfinite(local.x) || !std::isfinite(local.y)) return {};
  if (!std::isfinite(pressure)) pressure = 1.0f;
  pressure = std::clamp(pressure, 0.0f, 1.0f);
  if (!started_) return dabAt(local, pressure);

  StrokeUpdate u;
  const double step = std::max(1e-6, double(settings_.spacing) * settings_.radius);
  const glm::dvec2 from = last_;
  const double len = glm::length(local - from);
  // Distance along this segment of the next dab.
  double at = step - carried_;
  while (at <= len) {
    const double t = len > 0.0 ? at / len : 1.0;
    const float p = lastPressure_ + (pressure - lastPressure_) * float(t);
    double massError = 0.0;
    u.changed = u.changed.united(applyDab(from + (local - from) * t, p, &massError));
    u.erosionMassError += massError;
    ++u.dabs;
    at += step;
    if (u.dabs > 100000) break;  // a pen jump across a huge terrain with a tiny brush
  }
  carried_ = len - (at - step);
  last_ = local;
  lastPressure_ = pressure;
  u.changedBytes = bytesFor(u.changed);
  return u;
}

Region Stroke::applyDab(const glm::dvec2& local, float pressure, double* massError) {
  Heightfield& hf = terrain_.height;
  const double radius = settings_.pressureRadius ? std::max(settings_.radius * double(pressure), 0.5 * hf.spacing().x)
                                                 : settings_.radius;
  const float strength = settings_.pressureStrength ? settings_.strength * pressure : settings_.strength;
  DabContext ctx;
  ctx.hf = &hf;
  ctx.centreLocal = local;
  ctx.centre = local / hf.spacing();
  ctx.radius = radius;
  ctx.invRadius = hf.spacing() / radius;
  ctx.strength = strength;
  ctx.falloff = &falloff_;
  ctx.settings = &settings_;
  ctx.region = dabRegion(hf, local, radius);
  ctx.threads = threads_;
  ctx.recorder = &recorder_;
  if (ctx.region.empty()) return {};
  ++dabs_;

  const BrushTool tool = settings_.tool;
  if (tool == BrushTool::Paint) {
    recorder_.recordPaint(ctx.region);
    dabPaint(ctx, terrain_.paint, settings_.paintLayer, settings_.erase);
    total_ = total_.united(ctx.region);
    return ctx.region;
  }
  if (tool == BrushTool::Holes) {
    recorder_.recordHoles(ctx.region);
    dabHoles(ctx, settings_.erase);
    total_ = total_.united(ctx.region);
    return ctx.region;
  }
  if (tool == BrushTool::ThermalErosion || tool == BrushTool::HydraulicErosion) {
    ErosionMask mask = ErosionMask::circle(hf, local, radius, settings_.falloff);
    for (float& w : mask.weights) w *= std::clamp(strength, 0.0f, 1.0f);
    ErosionReport rep;
    if (tool == BrushTool::ThermalErosion) {
      rep = erodeThermal(hf, settings_.thermal, mask, &recorder_, nullptr, threads_);
    } else {
      HydraulicParams p = settings_.hydraulic;
      p.iterations = settings_.hydraulicIterationsPerDab;
      rep = erodeHydraulic(hf, p, mask, &recorder_, nullptr, threads_);
    }
    if (massError) *massError = rep.massError;
    total_ = total_.united(rep.changed);
    return rep.changed;
  }

  // Height tools: before-copies, then mark the tiles written (revision).
  recorder_.recordHeights(ctx.region);
  hf.heights().forEachTile(ctx.region, [&](int t, const Region&) { hf.heights().tileForWrite(t); });
  switch (tool) {
    case BrushTool::Raise: dabRaise(ctx, strength); break;
    case BrushTool::Lower: dabRaise(ctx, -strength); break;
    case BrushTool::Smooth: dabSmooth(ctx); break;
    case BrushTool::Flatten:
      if (!targetPicked_) {
        // Picked once per stroke (like Unreal): the height under the first
        // dab, or the plane fitted under it.
        if (settings_.flattenMode == FlattenMode::Slope) {
          flatten_ = fitPlane(ctx);
        } else {
          flatten_.mode = FlattenMode::Height;
          flatten_.height = settings_.flattenHeight ? *settings_.flattenHeight : hf.heightAtLocal(local);
        }
        targetPicked_ = true;
      }
      dabFlatten(ctx, flatten_, settings_.flattenDirection);
      break;
    case BrushTool::Noise: dabNoise(ctx, settings_.noise); break;
    case BrushTool::Terrace: dabTerrace(ctx, settings_.terrace); break;
    default: break;
  }
  hf.updateBounds(ctx.region);
  total_ = total_.united(ctx.region);
  return ctx.region;
}

UndoStep Stroke::finish() {
  finished_ = true;
  if (settings_.tool == BrushTool::Paint) terrain_.paint.releaseUniformTiles(total_);
  return recorder_.finish(std::string("terrain ") + toolName(settings_.tool));
}

RampResult applyRamp(Terrain& terrain, const RampSettings& in, int threads) {
  RampResult res;
  Heightfield& hf = terrain.height;
  RampSettings s = in;
  auto finite3 = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite3(s.a) || !finite3(s.b)) {
    res.error = "ramp end points must be finite";
    return res;
  }
  const glm::dvec2 a2(s.a), b2(s.b);
  const double len = glm::length(b2 - a2);
  if (len < 1e-6) {
    res.error = "ramp end points are the same point; drag out a ramp first";
    return res;
  }
  s.width = detail::clampParam(s.width, std::min(hf.spacing().x, hf.spacing().y), 1e7, 10.0, "ramp width (m)",
                               res.warnings);
  s.falloff = float(detail::clampParam(double(s.falloff), 0.0, 1.0, 0.3, "ramp falloff", res.warnings));
  s.strength = float(detail::clampParam(double(s.strength), 0.0, 1.0, 1.0, "ramp strength", res.warnings));

  // Bounding box of the ramp's rectangle (plus nothing: no round caps).
  const double half = 0.5 * s.width;
  const glm::dvec2 lo = glm::min(a2, b2) - glm::dvec2(half), hi = glm::max(a2, b2) + glm::dvec2(half);
  const glm::dvec2 sp = hf.spacing();
  const Region r = Region{int(std::ceil(lo.x / sp.x)), int(std::ceil(lo.y / sp.y)), int(std::floor(hi.x / sp.x)) + 1,
                          int(std::floor(hi.y / sp.y)) + 1}
                       .intersected(hf.bounds());
  if (r.empty()) {
    res.warnings.push_back("ramp lies outside the terrain");
    return res;
  }
  UndoRecorder rec(terrain);
  rec.recordHeights(r);
  hf.heights().forEachTile(r, [&](int t, const Region&) { hf.heights().tileForWrite(t); });
  const glm::dvec2 dir = (b2 - a2) / len;
  const double inner = half * (1.0 - double(s.falloff));
  auto& grid = hf.heights();
  parallelFor(r.height(), threads, 32, [&](int yb, int ye) {
    for (int y = r.y0 + yb; y < r.y0 + ye; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const glm::dvec2 p(x * sp.x, y * sp.y);
        const double u = glm::dot(p - a2, dir);  // metres along the ramp
        if (u < 0.0 || u > len) continue;
        const double side = std::abs(glm::dot(p - a2, glm::dvec2(-dir.y, dir.x)));
        if (side > half) continue;
        double w = 1.0;
        if (side > inner) {
          const double t = (side - inner) / std::max(1e-12, half - inner);
          const double q = 1.0 - t;
          w = q * q * (3.0 - 2.0 * q);
        }
        // Linear in u, computed in double from the end heights.
        const double target = s.a.z + (s.b.z - s.a.z) * (u / len);
        const double a = double(s.strength) * w;
        float* tile = grid.preparedTile(grid.tileIndex(x, y));
        float& h = tile[TileGrid<float>::localIndex(x, y)];
        h = a >= 1.0 ? float(target) : float((1.0 - a) * double(h) + a * target);
      }
  });
  hf.updateBounds(r);
  res.changed = r;
  res.undo = rec.finish("terrain ramp");
  return res;
}

}  // namespace hs::terrain
