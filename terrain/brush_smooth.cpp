// Smooth: blend toward a two-pass box blur (close to a Gaussian) of the
// heights. The blur is a weighted mean with positive weights summing to 1,
// computed with double running sums, and the blend is clamped to
// max(h, blur), so smoothing never raises a maximum nor lowers a minimum.
#include <algorithm>
#include <vector>

#include "terrain/brush_dab.h"

namespace hs::terrain {
namespace {

// Box blur of radius k from src into dst along rows (stride 1) or columns (stride w),
// clamping at the array edges.
void boxPass(std::vector<float>& src, std::vector<float>& dst, int w, int h, int k, bool horizontal, int threads) {
  const int len = horizontal ? w : h, lines = horizontal ? h : w;
  const size_t step = horizontal ? 1 : size_t(w), lineStep = horizontal ? size_t(w) : 1;
  const double inv = 1.0 / double(2 * k + 1);
  parallelFor(lines, threads, 32, [&](int lb, int le) {
    for (int l = lb; l < le; ++l) {
      const float* s = src.data() + size_t(l) * lineStep;
      float* d = dst.data() + size_t(l) * lineStep;
      auto at = [&](int i) { return double(s[size_t(std::clamp(i, 0, len - 1)) * step]); };
      double sum = 0.0;
      for (int i = -k; i <= k; ++i) sum += at(i);
      for (int i = 0; i < len; ++i) {
        d[size_t(i) * step] = float(sum * inv);
        sum += at(i + k + 1) - at(i - k);
      }
    }
  });
}

}  // namespace

void dabSmooth(const DabContext& ctx) {
  const Heightfield& hf = *ctx.hf;
  const double radiusSamples = ctx.radius / std::min(hf.spacing().x, hf.spacing().y);
  const int k = ctx.settings && ctx.settings->smoothKernel > 0
                    ? ctx.settings->smoothKernel
                    : std::max(1, int(radiusSamples / 10.0 + 0.5));
  // Two passes of radius k need 2k samples of context around the region.
  const Region src = ctx.region.expanded(2 * k).intersected(hf.bounds());
  const int w = src.width(), h = src.height();
  std::vector<float> a = hf.read(src), tmp(a.size());
  boxPass(a, tmp, w, h, k, true, ctx.threads);
  boxPass(tmp, a, w, h, k, false, ctx.threads);
  boxPass(a, tmp, w, h, k, true, ctx.threads);
  boxPass(tmp, a, w, h, k, false, ctx.threads);
  const float s = ctx.strength;
  forEachDabSample(ctx, [&](float& v, int x, int y, float wgt) {
    const float blur = a[size_t(y - src.y0) * size_t(w) + size_t(x - src.x0)];
    const float t = std::min(1.0f, s * wgt);
    const float out = (1.0f - t) * v + t * blur;
    v = std::clamp(out, std::min(v, blur), std::max(v, blur));
  });
}

}  // namespace hs::terrain
