#pragma once
// Instances follow the ground: after a terrain edit (a sculpt stroke, an
// erosion, a hole), the instances standing on the terrain where it changed
// move with it and those over a new hole are removed; the undo data joins
// the terrain edit's undo step (FoliageUndo::merge, or kept beside the
// terrain's UndoStep in the same command).
//
// An instance's anchor is where it met the surface: its position plus the
// type's sink depth along its up axis. Its height above the old surface
// at the anchor's XY is kept, and snapped to exactly the sink's share
// (-sink * up.z) when within 2 mm of it (the quantisation of the stored
// position and rotation), so an instance placed on the ground is put back
// on the new ground with one rounding (<= 0.49 mm), not an accumulating
// one; an instance moved off the ground by hand keeps its height above it.
#include "foliage/store.h"
#include "terrain/heightfield.h"
#include "terrain/region.h"

namespace hs::foliage {

struct FollowStats {
  size_t moved = 0, removed = 0, checked = 0;
};

// `before` and `after`: the terrain's heights before and after the edit
// (Terrain::clone() is copy-on-write, so a before copy costs pointers);
// `changed`: the samples the edit changed (the UndoStep's region()).
FoliageUndo followGround(FoliageStore& store, const terrain::Heightfield& before, const terrain::Heightfield& after,
                         const terrain::Region& changed, FollowStats* stats = nullptr);

}  // namespace hs::foliage
