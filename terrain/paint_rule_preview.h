#pragma once
// A rule's effect at a glance (the editor's rules list): its weight on a
// coarse grid of the terrain's own samples, and the share of the terrain it
// reaches. Cheap enough to recompute on every edit of a rule (a 96 x 96
// preview reads 9216 samples), and exact at the samples it reads: the same
// altitude, slope and weight applyPaintRules computes there.
#include <vector>

#include "terrain/heightfield.h"
#include "terrain/paint_rules.h"

namespace hs::terrain {

struct RulePreview {
  int width = 0, height = 0;
  std::vector<float> weights;  // row-major, row 0 = south, ruleWeight at the nearest sample
  double coverage = 0.0;       // share of preview samples with weight > 0
  double full = 0.0;           // share where the rule applies fully (weight >= strength)
};

// Samples `hf` at most `maxSize` per side (fewer for a smaller terrain),
// keeping its aspect. A disabled rule previews as zero everywhere.
RulePreview previewRule(const Heightfield& hf, const PaintRule& rule, int maxSize = 96);

}  // namespace hs::terrain
