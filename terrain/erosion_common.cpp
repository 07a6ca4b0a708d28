#include "terrain/erosion_common.h"

#include <algorithm>
#include <cmath>

#include "terrain/brush_dab.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

ErosionMask ErosionMask::whole(const Heightfield& hf) { return ErosionMask{hf.bounds(), {}}; }

ErosionMask ErosionMask::clipped(const Region& r) const {
  ErosionMask m;
  m.region = region.intersected(r);
  if (weights.empty() || m.region == region) {
    m.weights = m.region == region ? weights : std::vector<float>{};
    return m;
  }
  m.weights.resize(m.region.samples());
  for (int y = m.region.y0; y < m.region.y1; ++y)
    for (int x = m.region.x0; x < m.region.x1; ++x)
      m.weights[size_t(y - m.region.y0) * size_t(m.region.width()) + size_t(x - m.region.x0)] = at(x, y);
  return m;
}

ErosionMask ErosionMask::circle(const Heightfield& hf, const glm::dvec2& c, double radius,
                                const FalloffCurve& curve) {
  ErosionMask m;
  const glm::dvec2 sp = hf.spacing();
  if (!(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(c.x) || !std::isfinite(c.y)) return m;
  const glm::dvec2 cs = c / sp, rs = glm::dvec2(radius) / sp;
  m.region = dabRegion(hf, c, radius);
  m.weights.resize(m.region.samples());
  const FalloffTable table(curve);
  for (int y = m.region.y0; y < m.region.y1; ++y)
    for (int x = m.region.x0; x < m.region.x1; ++x) {
      const double dx = (x - cs.x) / rs.x, dy = (y - cs.y) / rs.y;
      m.weights[size_t(y - m.region.y0) * size_t(m.region.width()) + size_t(x - m.region.x0)] =
          table.weight(float(dx * dx + dy * dy));
    }
  return m;
}

ErosionMask ErosionMask::fromPaintLayer(const PaintLayers& paint, int layer, const Region& region) {
  ErosionMask m;
  const Region all{0, 0, paint.samplesX(), paint.samplesY()};
  m.region = region.empty() ? all : region.intersected(all);
  if (layer < 0 || layer >= paint.layerCount()) {
    m.region = {};
    return m;
  }
  m.weights.resize(m.region.samples());
  for (int y = m.region.y0; y < m.region.y1; ++y)
    for (int x = m.region.x0; x < m.region.x1; ++x)
      m.weights[size_t(y - m.region.y0) * size_t(m.region.width()) + size_t(x - m.region.x0)] =
          paint.weight(layer, x, y);
  return m;
}

namespace detail {

size_t sanitizeHeights(std::vector<float>& h, int w, int hgt) {
  size_t fixed = 0;
  for (int y = 0; y < hgt; ++y)
    for (int x = 0; x < w; ++x) {
      float& v = h[size_t(y) * size_t(w) + size_t(x)];
      if (std::isfinite(v)) continue;
      double sum = 0.0;
      int n = 0;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= hgt) continue;
        const float n4 = h[size_t(ny[k]) * size_t(w) + size_t(nx[k])];
        if (std::isfinite(n4)) {
          sum += double(n4);
          ++n;
        }
      }
      v = n ? float(sum / n) : 0.0f;
      ++fixed;
    }
  return fixed;
}

double sumHeights(const std::vector<float>& h, int w, int hgt) {
  double total = 0.0;
  for (int y = 0; y < hgt; ++y) {
    double row = 0.0;
    const float* p = h.data() + size_t(y) * size_t(w);
    for (int x = 0; x < w; ++x) row += double(p[x]);
    total += row;
  }
  return total;
}

double clampParam(double v, double lo, double hi, double fallback, const char* name,
                  std::vector<std::string>& warnings) {
  // Brush and ramp settings have ranges that depend on the terrain (the
  // radius on its spacing): a declaration made for the call.
  const ParamDecl p{.key = name, .label = name, .min = lo, .max = hi, .defaultValue = fallback};
  return hs::clampParam(p, v, warnings);
}

void finishReport(ErosionReport& rep, const std::vector<float>& h, int w, int hgt, double cellArea, double absSum,
                  std::chrono::steady_clock::time_point start) {
  rep.massAfter = sumHeights(h, w, hgt) * cellArea;
  rep.massError = std::abs(rep.massAfter - rep.massBefore);
  rep.relativeMassError = absSum > 0.0 ? rep.massError / (absSum * cellArea) : rep.massError;
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rep.cellIterationsPerSecond =
      rep.seconds > 0.0 ? double(w) * double(hgt) * double(rep.iterationsDone) / rep.seconds : 0.0;
}

ErosionReport erodeWindow(Heightfield& hf, const ErosionMask& maskIn, UndoRecorder* recorder, const GridSolver& solve) {
  const ErosionMask mask = maskIn.clipped(hf.bounds());
  const Region win = mask.region;
  if (win.width() < 2 || win.height() < 2) {
    ErosionReport r;
    r.warnings.push_back("erosion region is smaller than 2x2 samples; nothing to do");
    return r;
  }
  std::vector<float> h = hf.read(win);
  ErosionReport rep = solve(h, win.width(), win.height(), mask.weights.empty() ? nullptr : mask.weights.data());
  if (rep.cancelled) return rep;
  if (recorder) recorder->recordHeights(win);
  hf.write(win, h);
  rep.changed = win;
  return rep;
}

}  // namespace detail
}  // namespace hs::terrain
