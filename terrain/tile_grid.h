#pragma once
// A 2D array of samples stored as square tiles of kTileSize x kTileSize.
//
// Why tiles: DESIGN.md wants a save after one stroke to write a few tiles and
// undo to keep only the tiles a stroke touched. Why 128: undo memory and save
// size are the touched area rounded up to whole tiles; a radius-16 dab copies
// 64-256 KiB (1-4 tiles) where 256-tiles would copy 256 KiB-1 MiB, a
// radius-128 dab at most 9 tiles (576 KiB). 64-tiles would make an 8193^2
// terrain 16,900 blobs of 16 KiB, where per-blob overhead starts to matter;
// 128 gives 65 x 65 = 4225 tiles of 64 KiB, and 128 quads is a natural CDLOD
// node size, so per-tile bounds feed the quadtree directly.
//
// Tiles are allocated on first write. An unallocated tile reads as the grid's
// fill value: a paint layer nobody painted or a holes mask with no holes costs
// nothing. Each tile has a revision number that changes whenever it is written,
// which is how the scene file finds the tiles to save.
//
// Tiles are shared copy-on-write: clone() copies tile pointers, not samples,
// and the first write to a shared tile copies it. That makes a snapshot of a
// whole 8k terrain O(tiles) (the editor saves and erodes from snapshots on
// worker threads while the user keeps painting), and a new flat terrain is
// one shared tile until it is edited. Thread rule: one thread writes a grid
// (and takes snapshots of it); other threads may read and drop snapshots.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "terrain/region.h"

namespace hs::terrain {

constexpr int kTileShift = 7;
constexpr int kTileSize = 1 << kTileShift;  // 128 samples
constexpr int kTileMask = kTileSize - 1;
constexpr int kTileSamples = kTileSize * kTileSize;

template <class T>
class TileGrid {
 public:
  using TilePtr = std::shared_ptr<T[]>;

  TileGrid() = default;
  TileGrid(int width, int height, T fill, bool dense)
      : width_(width), height_(height), fill_(fill) {
    tilesX_ = (width + kTileSize - 1) >> kTileShift;
    tilesY_ = (height + kTileSize - 1) >> kTileShift;
    tiles_.resize(size_t(tilesX_) * size_t(tilesY_));
    revision_.assign(tiles_.size(), 0);
    if (dense) {
      // One tile of fill values shared by all; writes copy it (see above).
      const TilePtr shared = newTile();
      for (auto& t : tiles_) t = shared;
    }
  }

  TileGrid(TileGrid&&) noexcept = default;
  TileGrid& operator=(TileGrid&&) noexcept = default;
  // Same samples and revisions; tiles are shared until either side writes.
  TileGrid clone() const {
    TileGrid g;
    g.width_ = width_; g.height_ = height_; g.tilesX_ = tilesX_; g.tilesY_ = tilesY_;
    g.fill_ = fill_; g.revision_ = revision_; g.revisionCounter_ = revisionCounter_;
    g.tiles_ = tiles_;
    return g;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }
  int tileCount() const { return int(tiles_.size()); }
  T fill() const { return fill_; }
  static int tileIndexOf(int tilesX, int x, int y) { return (y >> kTileShift) * tilesX + (x >> kTileShift); }
  int tileIndex(int x, int y) const { return tileIndexOf(tilesX_, x, y); }
  int tileIndexOfTile(int tx, int ty) const { return ty * tilesX_ + tx; }
  static int localIndex(int x, int y) { return ((y & kTileMask) << kTileShift) | (x & kTileMask); }

  // Samples of tile `t` that lie inside the grid.
  Region tileRegion(int t) const {
    const int tx = t % tilesX_, ty = t / tilesX_;
    return Region{tx * kTileSize, ty * kTileSize, std::min(width_, (tx + 1) * kTileSize),
                  std::min(height_, (ty + 1) * kTileSize)};
  }

  T get(int x, int y) const {
    const T* t = tiles_[size_t(tileIndex(x, y))].get();
    return t ? t[localIndex(x, y)] : fill_;
  }
  // Writes one sample (allocates and marks its tile). For bulk work use
  // tileForWrite() once per tile and write through the pointer.
  void set(int x, int y, T v) { tileForWrite(tileIndex(x, y))[localIndex(x, y)] = v; }

  // Read access; nullptr means "every sample is fill()".
  const T* tile(int t) const { return tiles_[size_t(t)].get(); }
  // Write access: allocates the tile if needed (copies it if it is shared
  // with a clone) and bumps its revision.
  T* tileForWrite(int t) {
    auto& p = tiles_[size_t(t)];
    if (!p) {
      p = newTile();
    } else if (p.use_count() > 1) {
      TilePtr copy(new T[kTileSamples]);
      std::memcpy(copy.get(), p.get(), sizeof(T) * kTileSamples);
      p = std::move(copy);
    } else {
      // use_count() is a relaxed load; the fence pairs it with the release
      // of the last other owner (a worker dropping its snapshot), so that
      // worker's reads happen before this write.
      std::atomic_thread_fence(std::memory_order_acquire);
    }
    touch(t);
    return p.get();
  }
  // Write access without bookkeeping, for worker threads after the calling
  // thread prepared the tile with tileForWrite() (which is not thread-safe).
  T* preparedTile(int t) { return tiles_[size_t(t)].get(); }
  bool allocated(int t) const { return tiles_[size_t(t)] != nullptr; }
  // The tile's storage itself (shared, read-only), for snapshots and for
  // moving a worker's result into the live grid (setTile).
  const TilePtr& sharedTile(int t) const { return tiles_[size_t(t)]; }

  TilePtr copyTile(int t) const {
    const T* src = tiles_[size_t(t)].get();
    if (!src) return nullptr;
    TilePtr p(new T[kTileSamples]);
    std::memcpy(p.get(), src, sizeof(T) * kTileSamples);
    return p;
  }
  // Exchanges tile storage (undo/redo): O(1), bitwise exact.
  void swapTile(int t, TilePtr& other) {
    std::swap(tiles_[size_t(t)], other);
    touch(t);
  }
  // Replaces a tile's content (used by decoding and undo).
  void setTile(int t, TilePtr p) {
    tiles_[size_t(t)] = std::move(p);
    touch(t);
  }
  // Frees a tile whose every sample equals fill() (after painting a layer away).
  bool releaseIfUniform(int t) {
    const T* p = tiles_[size_t(t)].get();
    if (!p) return false;
    for (int i = 0; i < kTileSamples; ++i)
      if (p[i] != fill_) return false;
    tiles_[size_t(t)].reset();
    touch(t);
    return true;
  }

  void touch(int t) { revision_[size_t(t)] = ++revisionCounter_; }
  uint64_t revision(int t) const { return revision_[size_t(t)]; }
  // Monotonic per grid: remember it at save time, then tiles with a larger
  // revision are the ones to write.
  uint64_t revisionCounter() const { return revisionCounter_; }
  std::vector<int> tilesChangedSince(uint64_t revision) const {
    std::vector<int> out;
    for (size_t i = 0; i < revision_.size(); ++i)
      if (revision_[i] > revision) out.push_back(int(i));
    return out;
  }

  size_t allocatedTiles() const {
    return size_t(std::count_if(tiles_.begin(), tiles_.end(), [](const TilePtr& p) { return p != nullptr; }));
  }
  size_t memoryBytes() const { return allocatedTiles() * sizeof(T) * kTileSamples; }
  static constexpr size_t tileBytes() { return sizeof(T) * kTileSamples; }

  // Calls fn(tileIndex, tileRegion ∩ r) for every tile under `r`.
  template <class Fn>
  void forEachTile(Region r, Fn&& fn) const {
    r = r.intersected(Region{0, 0, width_, height_});
    if (r.empty()) return;
    for (int ty = r.y0 >> kTileShift; ty <= (r.y1 - 1) >> kTileShift; ++ty)
      for (int tx = r.x0 >> kTileShift; tx <= (r.x1 - 1) >> kTileShift; ++tx) {
        const int t = ty * tilesX_ + tx;
        fn(t, tileRegion(t).intersected(r));
      }
  }

 private:
  TilePtr newTile() const {
    TilePtr p(new T[kTileSamples]);
    std::fill(p.get(), p.get() + kTileSamples, fill_);
    return p;
  }

  int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
  T fill_{};
  std::vector<TilePtr> tiles_;
  std::vector<uint64_t> revision_;
  uint64_t revisionCounter_ = 0;
};

}  // namespace hs::terrain
