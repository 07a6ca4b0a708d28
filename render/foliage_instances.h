#pragma once
// The document's foliage (scene/foliage_data.h) as the instanced draw
// source's input (instanced_source.h): per foliage type an InstanceType
// (its mesh asset by name, cull distance, fade, wind, shadows), per store
// cell its world origin (exact in double: a cell's origin is its key times
// 64 m), per instance a GpuInstance: the position in the cell (the store's
// 2^-10 m steps are exact in float up to 64 m), the rotation and scale the
// store decodes, the type and the stable id. GL-free, so tests compare what
// the renderer is given with the store itself.
//
// A GpuInstance names its cell in 16 bits: a set holds at most 65,536
// cells, so a store with more (a forest over 27 km² of 64 m columns, one
// layer high) becomes several sets, one source each; and a source culls at
// most kMaxInstancesPerSource (about 4.2M) instances, so a store with more
// becomes several sets too (whole cells each).
#include <vector>

#include "render/instanced_source.h"
#include "scene/scene_state.h"

namespace hs::render {

constexpr size_t kMaxCellsPerSet = 65536;

// The sets the state's foliage draws as (empty: none). Cells in key order,
// so the result is the same for the same store.
// `maxInstances`: the instances a set holds at most (tests make it small);
// a cell with more than that alone is a set of its own.
std::vector<InstanceSet> foliageInstanceSets(const scene::SceneState& state,
                                             size_t maxInstances = kMaxInstancesPerSource);

}  // namespace hs::render
