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
//
// Paged sets (what the renderer keeps, foliage_sources.h): each cell gets
// a slot of room, its instances then spare ones (kSpareInstance: a type no
// set has, which culling skips and nothing draws), so an edit rewrites the
// slots of the cells it touched in place and the frame uploads those
// ranges, not the set; and each set ends in a tail of spare places from
// which a cell painted later takes its slot.
#include <unordered_map>
#include <vector>

#include "foliage/instance.h"
#include "render/instanced_source.h"
#include "scene/scene_state.h"

namespace hs::render {

constexpr size_t kMaxCellsPerSet = 65536;
// An unused place in a cell's slot: type 0xFFFF (the store allows 65,535
// types, 0 .. 65,534), so the culling passes skip it.
inline const GpuInstance kSpareInstance = [] {
  GpuInstance g;
  g.typeAndCell = 0xFFFFu;
  return g;
}();

// Per foliage type of the state, how it is drawn (empty: no foliage).
std::vector<InstanceType> foliageInstanceTypes(const scene::SceneState& state);

// The sets the state's foliage draws as (empty: none), tight (no spare
// places). Cells in key order, so the result is the same for the same store.
// `maxInstances`: the instances a set holds at most (tests make it small);
// a cell with more than that alone is a set of its own.
std::vector<InstanceSet> foliageInstanceSets(const scene::SceneState& state,
                                             size_t maxInstances = kMaxInstancesPerSource);

// Where a cell's instances sit in a paged set: places [first, first +
// room) of set `set`'s instances, the first `count` live, the rest spare;
// `cell` its index in the set's cells; `revision` the store's
// cellRevision it was packed from.
struct CellSlot {
  size_t set = 0;
  uint16_t cell = 0;
  size_t first = 0, count = 0, room = 0;
  uint64_t revision = 0;
};
using CellSlots = std::unordered_map<foliage::CellKey, CellSlot, foliage::CellKeyHash>;
// The room a cell of `count` instances gets: a quarter more and 16, so
// most brush dabs fit without a rebuild.
size_t cellRoom(size_t count);
// The spare places a paged set of `places` (its cells' rooms) keeps at
// its end for cells painted later: an eighth more and 4096, within
// `maxInstances`.
size_t setTail(size_t places, size_t maxInstances);
// The paged sets of the state's foliage, and every cell's slot in them;
// `tails` gets each set's first spare place of its tail (setTail).
std::vector<InstanceSet> foliagePagedSets(const scene::SceneState& state, CellSlots& slots,
                                          std::vector<size_t>& tails,
                                          size_t maxInstances = kMaxInstancesPerSource);
// Cell `key` as the store has it now, packed for its slot into `out`
// (slot.room places: its instances, then spare ones; none left: it was
// removed), the slot's count and revision updated. False, changing
// nothing, when they no longer fit its room.
bool repackCell(const foliage::FoliageStore& store, const foliage::CellKey& key, CellSlot& slot,
                std::vector<GpuInstance>& out);

}  // namespace hs::render
