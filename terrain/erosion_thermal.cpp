#include "terrain/erosion_thermal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/parallel.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

namespace {

struct Neighbour {
  int dx, dy;
  float dist;
};

}  // namespace

ErosionReport erodeThermalGrid(std::vector<float>& h, int w, int hgt, glm::dvec2 spacing,
                               const ThermalParams& in, const float* mask, const Progress* progress,
                               int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  ErosionReport rep;
  const ThermalParams p = in.sanitized(rep.warnings);
  rep.iterationsRequested = p.iterations;
  rep.threads = resolveThreads(threads);
  if (w < 2 || hgt < 2 || h.size() != size_t(w) * size_t(hgt)) return rep;
  if (!(spacing.x > 0.0 && spacing.y > 0.0)) spacing = glm::dvec2(1.0);
  rep.nonFiniteHeightsFixed = detail::sanitizeHeights(h, w, hgt);
  if (rep.nonFiniteHeightsFixed)
    rep.warnings.push_back(std::to_string(rep.nonFiniteHeightsFixed) +
                           " non-finite heights replaced by the mean of their neighbours");

  const double cellArea = spacing.x * spacing.y;
  rep.massBefore = detail::sumHeights(h, w, hgt) * cellArea;
  double absSum = 0.0;
  for (float v : h) absSum += std::abs(double(v));

  // Talus as a height difference per neighbour distance; 90 degrees means
  // "never": use +inf so no excess is ever positive.
  const double tanT = p.talusDegrees >= 90.0 ? std::numeric_limits<double>::infinity() : std::tan(p.talusDegrees * M_PI / 180.0);
  const float sx = float(spacing.x), sy = float(spacing.y), sd = float(std::hypot(spacing.x, spacing.y));
  const Neighbour nb[8] = {{-1, 0, sx}, {1, 0, sx}, {0, -1, sy}, {0, 1, sy},
                           {-1, -1, sd}, {1, -1, sd}, {-1, 1, sd}, {1, 1, sd}};
  float talusDiff[8];
  for (int j = 0; j < 8; ++j) talusDiff[j] = float(tanT * double(nb[j].dist));

  // Heights = base (the input, fixed) + delta (what erosion moved). The
  // differences that drive the scheme are formed as (base difference) +
  // (delta difference), and moves accumulate in delta, whose float
  // resolution follows the size of the change: tiny steps still move
  // material on a terrain 1000 m high instead of rounding away.
  const std::vector<float>& base = h;
  std::vector<float> k(h.size(), 0.0f), delta(h.size(), 0.0f), next(h.size());
  const float strength = p.strength;
  auto idx = [w](int x, int y) { return size_t(y) * size_t(w) + size_t(x); };
  auto inMask = [&](size_t i) { return !mask || mask[i] > 0.0f; };
  // Excess of the difference from a to b over the talus difference (0 if none).
  auto excess = [&](size_t a, size_t b, int j) {
    const float e = ((base[a] - base[b]) + (delta[a] - delta[b])) - talusDiff[j];
    return e > 0.0f ? e : 0.0f;
  };

  // Per-sample kernels, written once with a compile-time switch: border
  // samples check their neighbours' bounds, interior samples (nearly all)
  // do not. Both run the same arithmetic in the same order, so the split
  // cannot change a bit of the result.
  const ptrdiff_t off[8] = {-1, 1, -ptrdiff_t(w), ptrdiff_t(w), -ptrdiff_t(w) - 1, -ptrdiff_t(w) + 1,
                            ptrdiff_t(w) - 1, ptrdiff_t(w) + 1};
  auto pass1 = [&](int x, int y, auto checked) {
    const size_t i = idx(x, y);
    float kk = 0.0f;
    if (inMask(i)) {
      float sum = 0.0f, mx = 0.0f;
      for (int j = 0; j < 8; ++j) {
        if constexpr (decltype(checked)::value) {
          const int nx = x + nb[j].dx, ny = y + nb[j].dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= hgt) continue;
        }
        const size_t n = size_t(ptrdiff_t(i) + off[j]);
        if (!inMask(n)) continue;
        const float e = excess(i, n, j);
        sum += e;
        mx = std::max(mx, e);
      }
      if (sum > 0.0f) {
        kk = strength * std::min(0.125f, 0.5f * mx / sum);
        if (mask) kk *= std::min(mask[i], 1.0f);
      }
    }
    k[i] = kk;
  };
  auto pass2 = [&](int x, int y, auto checked) {
    const size_t i = idx(x, y);
    float out = 0.0f, inflow = 0.0f;
    if (inMask(i)) {
      const float ki = k[i];
      for (int j = 0; j < 8; ++j) {
        if constexpr (decltype(checked)::value) {
          const int nx = x + nb[j].dx, ny = y + nb[j].dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= hgt) continue;
        }
        const size_t n = size_t(ptrdiff_t(i) + off[j]);
        if (!inMask(n)) continue;
        if (ki > 0.0f) out += ki * excess(i, n, j);
        // Neighbour n sees this sample in the opposite direction, which
        // has the same distance (so the same talus difference).
        if (k[n] > 0.0f) inflow += k[n] * excess(n, i, j);
      }
    }
    next[i] = delta[i] - out + inflow;
  };
  using Checked = std::true_type;
  using Fast = std::false_type;
  auto pass1Checked = [&](int x, int y) { pass1(x, y, Checked{}); };
  auto pass1Fast = [&](int x, int y) { pass1(x, y, Fast{}); };
  auto pass2Checked = [&](int x, int y) { pass2(x, y, Checked{}); };
  auto pass2Fast = [&](int x, int y) { pass2(x, y, Fast{}); };
  auto forRow = [&](int y, auto&& border, auto&& interior) {
    if (y == 0 || y == hgt - 1) {
      for (int x = 0; x < w; ++x) border(x, y);
      return;
    }
    border(0, y);
    for (int x = 1; x < w - 1; ++x) interior(x, y);
    border(w - 1, y);
  };

  for (int it = 0; it < p.iterations; ++it) {
    if (isCancelled(progress)) {
      rep.cancelled = true;
      break;
    }
    // Pass 1: share factor k per sample.
    parallelFor(hgt, threads, 8, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) forRow(y, pass1Checked, pass1Fast);
    });
    // Pass 2: gather. Sender and receiver compute each transfer with the
    // same expression k_src * excess(src, dst), so they agree to the bit.
    parallelFor(hgt, threads, 8, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) forRow(y, pass2Checked, pass2Fast);
    });
    delta.swap(next);
    rep.iterationsDone = it + 1;
    if (progress && (it % 16 == 0 || it + 1 == p.iterations))
      progress->report(double(it + 1) / double(std::max(1, p.iterations)), "thermal erosion");
  }

  for (size_t i = 0; i < h.size(); ++i) h[i] = float(double(h[i]) + double(delta[i]));
  detail::finishReport(rep, h, w, hgt, cellArea, absSum, t0);
  return rep;
}

ErosionReport erodeThermal(Heightfield& hf, const ThermalParams& params, const ErosionMask& mask,
                           UndoRecorder* recorder, const Progress* progress, int threads) {
  return detail::erodeWindow(hf, mask, recorder, [&](std::vector<float>& h, int w, int hgt, const float* weights) {
    return erodeThermalGrid(h, w, hgt, hf.spacing(), params, weights, progress, threads);
  });
}

}  // namespace hs::terrain
