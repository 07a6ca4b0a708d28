#pragma once
// Automatic painting by altitude and slope (World Machine / Gaea style
// "auto-splat"). Each rule says where its layer goes; rules apply in order,
// each one painting its layer with the rule's weight through the same blend
// as the brush, so later rules cover earlier ones and weights sum to 1.
#include <string>
#include <vector>

#include "core/progress.h"
#include "terrain/region.h"
#include "terrain/terrain.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

struct PaintRule {
  int layer = 0;
  bool enabled = true;
  // Altitude band in world metres (origin.z + height). Outside the band the
  // weight falls to 0 over `altitudeBlend` metres (smoothstep).
  bool useAltitude = false;
  double altitudeMin = 0.0, altitudeMax = 1000.0, altitudeBlend = 10.0;
  // Slope band in degrees, blending over `slopeBlend` degrees.
  bool useSlope = false;
  double slopeMin = 0.0, slopeMax = 30.0, slopeBlend = 5.0;
  float strength = 1.0f;  // 0..1, how far toward the layer where the rule fully applies
  bool operator==(const PaintRule&) const = default;
};

// Weight of one rule at a given altitude (world metres) and slope (degrees).
float ruleWeight(const PaintRule& rule, double altitude, double slopeDegrees);

struct PaintRulesResult {
  Region changed;
  UndoStep undo;
  std::vector<std::string> warnings;
  std::string error;
  bool cancelled = false;  // nothing changed
  bool ok() const { return error.empty(); }
};

// Applies `rules` over `region` (whole terrain by default).
PaintRulesResult applyPaintRules(Terrain& terrain, const std::vector<PaintRule>& rules, Region region = {},
                                 const Progress* progress = nullptr, int threads = 0);

// A layer's weights as a mask for other systems (the foliage issue): one
// float in [0,1] per sample of `region`, row-major, row 0 = south.
struct LayerMask {
  Region region;
  std::vector<float> values;
  float at(int x, int y) const {
    return values[size_t(y - region.y0) * size_t(region.width()) + size_t(x - region.x0)];
  }
};
Result<LayerMask> exportLayerMask(const PaintLayers& paint, int layer, Region region = {});

}  // namespace hs::terrain
