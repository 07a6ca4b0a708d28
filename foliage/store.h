#pragma once
// A scene's foliage: its types and their instances, kept in 64 m cells
// (instance.h: cells are cubes keyed by integer coordinates, instances
// 16-byte records relative to their cell), with stable ids, dirty tracking
// for saves and per-cell undo (docs/foliage.md, "Storage").
//
// Cell blob (little endian), what the .hscene keeps per cell:
//   "HSFC" | u16 version=1 | u16 runs | i32 cx, cy, cz | u32 instances
//   | u32 raw bytes | u32 payload bytes | u64 XXH3 of the raw payload | payload
// payload: the raw bytes as a zlib stream (libdeflate). raw: per run
// (u16 type, u8 surface, u8 0, u32 count), then per run its records with
// ids delta-coded (id - previous id, mod 2^32) and split into 16 byte
// planes (byte b of every record together), which deflate packs tighter.
// A decoder checks every field, the sizes and the hash, and names the cell
// and the byte offset of what is wrong; nothing of a bad blob is loaded.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "foliage/foliage_type.h"
#include "foliage/instance.h"

namespace hs::foliage {

struct Status {
  std::string error;  // empty: success
  bool ok() const { return error.empty(); }
  explicit operator bool() const { return ok(); }
};

// The records of one (type, surface) pair in a cell.
struct Run {
  uint16_t type = 0;
  Surface surface = Surface::Terrain;
  std::vector<PackedInstance> items;
  bool operator==(const Run&) const = default;
};

struct Cell {
  std::vector<Run> runs;
  size_t count() const;
  bool empty() const { return count() == 0; }
  // The run for (type, surface), made when missing.
  Run& run(uint16_t type, Surface surface);
  bool operator==(const Cell&) const = default;
};

std::string cellName(const CellKey& k);      // "(3, -2, 0)"
std::string cellBlobKey(const CellKey& k);   // "foliage/cell/3_-2_0"

constexpr size_t kCellHeaderBytes = 40;
// The blob of a cell (see above); `level` is libdeflate's (1 fastest .. 12).
std::vector<uint8_t> encodeCell(const CellKey& key, const Cell& cell, int level = 4);
// Decodes a blob. `expected` (the key the file stores it under) names the
// cell in messages and must match the header's; `typeCount` bounds the
// type indices.
Status decodeCell(std::span<const uint8_t> blob, const CellKey& expected, size_t typeCount, Cell& out);

class FoliageStore;

// The undo data of one edit: the cells it touched as they were before it
// (absent: the cell did not exist) and the next id. Undo and redo are the
// same swap with the store, bitwise exact.
class FoliageUndo {
 public:
  bool empty() const { return cells_.empty(); }
  size_t cellCount() const { return cells_.size(); }
  size_t bytes() const;
  std::vector<CellKey> keys() const;
  // Exchanges the stored cells (and next id) with the store's.
  void swap(FoliageStore& store);
  // Appends a later edit's data to this step (same undo step, e.g. the
  // ground following of a sculpt): the earliest before of a cell wins.
  void merge(FoliageUndo&& later);

 private:
  friend class FoliageStore;
  struct Entry {
    CellKey key;
    std::optional<Cell> cell;
  };
  std::vector<Entry> cells_;
  std::unordered_set<CellKey, CellKeyHash> recorded_;
  uint32_t nextId_ = 0;
  bool hasNextId_ = false;
};

struct SaveSet {
  std::vector<CellKey> write;                // cells to write ...
  std::vector<std::vector<uint8_t>> blobs;   // ... their blobs
  std::vector<CellKey> remove;               // cells the file holds that no longer exist
  size_t bytes() const;
};

class FoliageStore {
 public:
  FoliageStore() = default;

  // --- types --------------------------------------------------------------
  const std::vector<FoliageType>& types() const { return types_; }
  const FoliageType& type(size_t i) const { return types_[i]; }
  // Adds a type (sanitized; warnings appended); returns its index, or -1
  // with an error when the name is taken or there are 65535 types.
  int addType(const FoliageType& t, std::vector<std::string>& messages);
  int findType(const std::string& name) const;
  // Puts back a types list as it was (the undo of a type edit): no checks,
  // the records must name only types the list has.
  void setTypes(std::vector<FoliageType> types) { types_ = std::move(types); }
  // Replaces a type's settings; a changed scale mode re-encodes its records.
  void setType(size_t i, const FoliageType& t, FoliageUndo* undo, std::vector<std::string>& warnings);

  // --- instances ----------------------------------------------------------
  size_t instanceCount() const;
  size_t instanceCount(uint16_t type) const;
  size_t cellCount() const { return cells_.size(); }
  const Cell* cell(const CellKey& k) const;
  const std::unordered_map<CellKey, Cell, CellKeyHash>& cells() const { return cells_; }
  // Calls fn(key, cell) for each cell whose XY footprint meets the world
  // rectangle [lo, hi] (any height).
  void forEachCellIn(const glm::dvec2& lo, const glm::dvec2& hi,
                     const std::function<void(const CellKey&, const Cell&)>& fn) const;
  std::vector<CellKey> cellsIn(const glm::dvec2& lo, const glm::dvec2& hi) const;
  // Every instance decoded (type and surface filled in), in cell key order.
  std::vector<Instance> allInstances() const;
  // A number that changes with every change of cell `k` (an edit, an undo,
  // its removal) and never goes back to an earlier value, so a renderer
  // that kept the number with its copy of the cell knows whether the copy
  // is current. 0 for a cell never changed since the store was made.
  uint64_t cellRevision(const CellKey& k) const;
  std::optional<Instance> find(uint32_t id) const;

  // --- edits (the tools' building blocks) ------------------------------------
  // The cell to modify, recorded in `undo` before its first change (undo
  // may be null) and marked changed; made when missing.
  Cell& edit(const CellKey& k, FoliageUndo* undo);
  // Adds an instance with the next id (or in.id when keepId); returns the id.
  uint32_t add(Instance in, FoliageUndo* undo, bool keepId = false);
  // Removes empty cells among `keys` (after an edit).
  void prune(const std::vector<CellKey>& keys);
  uint32_t nextId() const { return nextId_; }
  void setNextId(uint32_t id) { nextId_ = id; }
  // Takes n consecutive ids (recording the next id in `undo`); returns the first.
  uint32_t takeIds(uint32_t n, FoliageUndo* undo);
  // Records the next id in `undo` (before an edit that takes ids).
  void recordNextId(FoliageUndo* undo) const;

  // --- saving ---------------------------------------------------------------
  // Cells changed since the last markSaved() (all cells before the first),
  // encoded; cells the last save wrote that are gone now are to remove.
  SaveSet dirty(unsigned threads = 0) const;
  size_t dirtyCount() const;
  void markSaved();
  // Loads a cell blob into the store (replacing the cell; counts as saved).
  Status load(const CellKey& key, std::span<const uint8_t> blob);

 private:
  friend class FoliageUndo;
  void setCell(const CellKey& k, std::optional<Cell> c);
  void touch(const CellKey& k);
  static uint64_t columnKey(int32_t x, int32_t y) { return (uint64_t(uint32_t(x)) << 32) | uint32_t(y); }

  std::vector<FoliageType> types_;
  std::unordered_map<CellKey, Cell, CellKeyHash> cells_;
  std::unordered_map<uint64_t, std::vector<int32_t>> columns_;  // (x, y) -> z of the cells there
  std::unordered_map<CellKey, uint64_t, CellKeyHash> revision_;  // per cell, bumped by every change
  std::unordered_map<CellKey, uint64_t, CellKeyHash> savedRevision_;
  uint64_t clock_ = 0;
  bool everSaved_ = false;
  uint32_t nextId_ = 1;
};

}  // namespace hs::foliage
