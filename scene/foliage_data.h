#pragma once
// A scene's foliage in the document: one foliage::FoliageStore (types and
// instances in 64 m cells, docs/foliage.md) that edits change in place.
//
// Why not a value in SceneState: a forest is millions of 16-byte records,
// and a ScenePatch holds whole before/after values. So SceneState refers to
// the store through a shared pointer (copies of the state share it), as it
// does for terrain tiles (terrain_data.h), and instance edits are undone by
// foliage::FoliageUndo swaps inside a FoliageCommand (foliage_command.h).
//
// Threads: written on one thread (the editor's UI thread, the CLI's only
// one). A save on a worker thread works on snapshot(), a copy.
//
// Renderers rebuild their instance buffers when revision() moved.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "foliage/store.h"
#include "scene/ids.h"

namespace hs::scene {

struct SceneState;

class FoliageData {
 public:
  FoliageData() = default;
  explicit FoliageData(foliage::FoliageStore store) : store_(std::move(store)) {}
  FoliageData(const FoliageData&) = delete;
  FoliageData& operator=(const FoliageData&) = delete;

  foliage::FoliageStore& store() { return store_; }
  const foliage::FoliageStore& store() const { return store_; }
  bool empty() const { return store_.types().empty() && store_.cellCount() == 0; }

  // Bumped by every change (an edit, an undo): what renderers compare. A
  // change also ends the description's say over the cells.
  uint64_t revision() const { return revision_; }
  void touch() {
    ++revision_;
    pendingManifest.reset();
  }

  // A copy (for saving on a worker thread while the user keeps editing).
  std::shared_ptr<FoliageData> snapshot() const;

  // The manifest a scene description gave (foliage/manifest.h), kept from
  // sceneFromJson until the file loader has read the cells from the
  // blobs; the description of such a store repeats it.
  std::optional<Json> pendingManifest;

 private:
  foliage::FoliageStore store_;
  uint64_t revision_ = 1;
};

// The state's foliage, made empty when it has none.
FoliageData& foliageOf(SceneState& state);
// The state's store, or nullptr when it has no foliage.
const foliage::FoliageStore* foliageStoreOf(const SceneState& state);

// The mesh asset a foliage type draws (by name); kNoAsset when none.
AssetId foliageTypeAsset(const SceneState& state, const foliage::FoliageType& type);

}  // namespace hs::scene
