#pragma once
// The renderer's instanced sources for the document's foliage
// (foliage_instances.h): kept across frames (their instance buffers persist
// in the frame graph's pool, so a frame without an edit uploads nothing)
// and brought up to date by the smallest change that does it:
//   - cells edited, removed or undone whose instances fit their slots'
//     room: only those slots are packed again and only they are uploaded
//     (InstancedSource::updateInstances), a brush dab's few cells instead
//     of the whole forest;
//   - a new cell (the first dab on bare ground) takes a slot from a set's
//     spare tail (foliage_instances.h setTail) and its cell is appended
//     (InstancedSource::addCell): only that slot is uploaded;
//   - a cell grown past its room, a new cell no tail has room for, a type
//     added or changed, a mesh renamed, another store: the paged sets are
//     rebuilt and uploaded.
// GPU culling (the compute passes of instanced_source.h). Include only
// inside render/.
#include <memory>
#include <vector>

#include "render/foliage_instances.h"
#include "render/instanced_source.h"
#include "scene/scene_state.h"

namespace hs::render {

class FoliageSources {
 public:
  // The sources for `state`'s foliage (empty: none), brought up to date.
  const std::vector<std::shared_ptr<InstancedSource>>& update(const scene::SceneState& state);
  // What the last update did: the cells packed again in place (0 after a
  // rebuild) and whether it rebuilt the sets (tests, benchmarks).
  size_t lastRepackedCells() const { return lastRepacked_; }
  bool lastRebuilt() const { return lastRebuilt_; }

 private:
  // Packs the changed cells again in place, new ones into a tail; false
  // when that cannot be done (a cell past its room, a new cell no tail
  // has room for): the caller rebuilds.
  bool repack(const foliage::FoliageStore& store);
  void rebuild(const scene::SceneState& state);

  // The store the sets were built from: weak, so a new document's store
  // at a freed one's address is never taken for it.
  std::weak_ptr<const scene::FoliageData> data_;
  uint64_t revision_ = 0;
  std::vector<InstanceType> types_;  // what the sets were built with
  CellSlots slots_;
  std::vector<size_t> tails_;  // per set: its tail's first spare place
  std::vector<std::shared_ptr<InstancedSource>> sources_;
  size_t lastRepacked_ = 0;
  bool lastRebuilt_ = false;
};

}  // namespace hs::render
