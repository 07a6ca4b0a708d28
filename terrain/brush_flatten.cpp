// Flatten: blend toward a target height (picked under the first dab) or a
// plane (fitted under the first dab, "flatten along the slope"). The blend
// (1 - t) * h + t * target gives the target exactly where t = 1.
#include <algorithm>

#include "terrain/brush_dab.h"

namespace hs::terrain {

void dabFlatten(const DabContext& ctx, const FlattenTarget& target, FlattenDirection dir) {
  const float s = ctx.strength;
  forEachDabSample(ctx, [&](float& h, int x, int y, float w) {
    const float t = std::min(1.0f, s * w);
    const float goal = target.at(x, y);
    float out = t >= 1.0f ? goal : (1.0f - t) * h + t * goal;
    if (dir == FlattenDirection::RaiseOnly) out = std::max(out, h);
    if (dir == FlattenDirection::LowerOnly) out = std::min(out, h);
    h = out;
  });
}

FlattenTarget fitPlane(const DabContext& ctx) {
  // Weighted least squares z = a + b*x + c*y, centred on the dab for
  // conditioning; sums in double.
  double sw = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
  const Heightfield& hf = *ctx.hf;
  for (int y = ctx.region.y0; y < ctx.region.y1; ++y)
    for (int x = ctx.region.x0; x < ctx.region.x1; ++x) {
      const double w = double(ctx.weight(x, y));
      if (w <= 0.0) continue;
      const double px = x - ctx.centre.x, py = y - ctx.centre.y, pz = double(hf.at(x, y));
      sw += w; sx += w * px; sy += w * py; sz += w * pz;
      sxx += w * px * px; sxy += w * px * py; syy += w * py * py;
      sxz += w * px * pz; syz += w * py * pz;
    }
  FlattenTarget t;
  t.mode = FlattenMode::Slope;
  if (sw <= 0.0) {
    t.a = double(hf.heightAtLocal(ctx.centreLocal));
    return t;
  }
  // Solve the 3x3 normal equations by Cramer's rule.
  const double m[3][3] = {{sw, sx, sy}, {sx, sxx, sxy}, {sy, sxy, syy}};
  const double r[3] = {sz, sxz, syz};
  auto det3 = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double D = det3(m);
  double coef[3] = {sz / sw, 0.0, 0.0};
  if (std::abs(D) > 1e-12 * sw * sw * sw) {
    for (int c = 0; c < 3; ++c) {
      double mc[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) mc[i][j] = j == c ? r[i] : m[i][j];
      coef[c] = det3(mc) / D;
    }
  }
  // Back from dab-centred to sample coordinates.
  t.b = coef[1];
  t.c = coef[2];
  t.a = coef[0] - coef[1] * ctx.centre.x - coef[2] * ctx.centre.y;
  return t;
}

}  // namespace hs::terrain
