// Paint and holes dabs.
#include "terrain/brush_dab.h"
#include "terrain/paint_layers.h"

namespace hs::terrain {

void dabPaint(const DabContext& ctx, PaintLayers& paint, int layer, bool erase) {
  if (layer < 0 || layer >= paint.layerCount()) return;
  paint.prepareBlend(ctx.region, layer);
  const Region r = ctx.region;
  const float s = erase ? -ctx.strength : ctx.strength;
  parallelFor(r.height(), ctx.threads, 32, [&](int b, int e) {
    for (int y = r.y0 + b; y < r.y0 + e; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const float w = ctx.weight(x, y);
        if (w > 0.0f) paint.blendPrepared(x, y, layer, s * w);
      }
  });
}

void dabHoles(const DabContext& ctx, bool erase) {
  // A sample becomes a hole where the brush weight passes one half, so the
  // falloff decides the hole's edge. Sparse tiles: main thread only.
  for (int y = ctx.region.y0; y < ctx.region.y1; ++y)
    for (int x = ctx.region.x0; x < ctx.region.x1; ++x)
      if (ctx.weight(x, y) * ctx.strength >= 0.5f) ctx.hf->setHole(x, y, !erase);
}

}  // namespace hs::terrain
