#pragma once
// One dab: the footprint of a brush at one point of a stroke, and the loop
// every height tool runs over it. The loop goes row by row (rows split across
// threads), tile by tile within a row, with the falloff from a table indexed
// by squared distance: a radius-128 dab (66k samples) costs a few hundred
// microseconds.
#include <cmath>

#include "core/parallel.h"
#include "terrain/brush.h"
#include "terrain/heightfield.h"

namespace hs::terrain {

class UndoRecorder;
class PaintLayers;

struct DabContext {
  Heightfield* hf = nullptr;
  glm::dvec2 centreLocal{0.0};  // metres relative to the terrain origin
  glm::dvec2 centre{0.0};       // in samples
  glm::dvec2 invRadius{1.0};    // per sample: spacing / radius (normalised offset per sample)
  double radius = 1.0;          // metres
  float strength = 0.0f;        // after pressure
  const FalloffTable* falloff = nullptr;
  const BrushSettings* settings = nullptr;
  Region region;                // samples under the circle (what the dab changes)
  int threads = 0;
  const UndoRecorder* recorder = nullptr;  // before-copies (terrace reads them)

  float weight(int x, int y) const {
    const float dx = float((x - centre.x) * invRadius.x), dy = float((y - centre.y) * invRadius.y);
    return falloff->weight(dx * dx + dy * dy);
  }
};

// Samples whose distance to the centre is below the radius, clipped to the grid.
Region dabRegion(const Heightfield& hf, const glm::dvec2& centreLocal, double radius);

// Calls fn(float& h, int x, int y, float w) for each sample with w > 0.
// Tiles must have been prepared (tileForWrite) by the calling thread.
template <class Fn>
void forEachDabSample(const DabContext& c, Fn&& fn) {
  auto& grid = c.hf->heights();
  const Region r = c.region;
  parallelFor(r.height(), c.threads, 32, [&](int b, int e) {
    for (int yy = b; yy < e; ++yy) {
      const int y = r.y0 + yy;
      const float dy = float((y - c.centre.y) * c.invRadius.y);
      const float dy2 = dy * dy;
      if (dy2 >= 1.0f) continue;
      for (int tx = r.x0 >> kTileShift; tx <= (r.x1 - 1) >> kTileShift; ++tx) {
        const int t = grid.tileIndexOfTile(tx, y >> kTileShift);
        float* row = grid.preparedTile(t) + TileGrid<float>::localIndex(0, y);
        const int xa = std::max(r.x0, tx * kTileSize), xb = std::min(r.x1, (tx + 1) * kTileSize);
        for (int x = xa; x < xb; ++x) {
          const float dx = float((x - c.centre.x) * c.invRadius.x);
          const float r2 = dx * dx + dy2;
          if (r2 >= 1.0f) continue;
          fn(row[x & kTileMask], x, y, c.falloff->weight(r2));
        }
      }
    }
  });
}

// The height tools. Each changes only samples inside ctx.region.
void dabRaise(const DabContext& ctx, float metres);
void dabSmooth(const DabContext& ctx);
// target(x, y) in local height; direction limits raise/lower.
struct FlattenTarget {
  FlattenMode mode = FlattenMode::Height;
  float height = 0.0f;
  // Slope mode: plane z = a + b * x + c * y over sample coordinates.
  double a = 0.0, b = 0.0, c = 0.0;
  float at(int x, int y) const { return mode == FlattenMode::Height ? height : float(a + b * x + c * y); }
};
void dabFlatten(const DabContext& ctx, const FlattenTarget& target, FlattenDirection dir);
// Plane fitted (least squares, falloff-weighted) to the heights under a dab.
FlattenTarget fitPlane(const DabContext& ctx);
void dabNoise(const DabContext& ctx, const FractalNoise& noise);
void dabTerrace(const DabContext& ctx, const TerraceOptions& opts);
float terraceHeight(float h, const TerraceOptions& opts);
void dabPaint(const DabContext& ctx, PaintLayers& paint, int layer, bool erase);
void dabHoles(const DabContext& ctx, bool erase);

}  // namespace hs::terrain
