// Raise / lower: h += metres * w. With w = 1 at the centre, a dab of
// strength s adds exactly s there, and s * falloff elsewhere.
#include "terrain/brush_dab.h"

namespace hs::terrain {

void dabRaise(const DabContext& ctx, float metres) {
  forEachDabSample(ctx, [metres](float& h, int, int, float w) { h += metres * w; });
}

}  // namespace hs::terrain
