#pragma once
// The edge-collapse loop. One engine per region of each level
// (region_levels.h), the last one over everything: a 4-ary heap holding each collapsible edge once,
// keyed by its quadric error. Re-evaluation is lazy: a collapse only marks
// the edges around the kept vertex dirty (no heap operation at all); a dirty
// edge is re-evaluated when it reaches the top, and if its new key is
// larger it is sifted down in place. An edge touched several times before
// it comes up is evaluated once, and no update costs a sift. The checks
// that need the neighbourhood (link condition, normals, slivers) run only
// for the edge at the top.
//
// Thread safety: an engine restricted to region R only collapses edges
// whose endpoints and both opposite vertices have all their faces in R, so
// every array element and every OpenMesh item it writes belongs to R, and
// engines of different regions run concurrently without locks.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "core/large_pages.h"
#include "core/progress.h"
#include "meshproc/decimation_state.h"

namespace hs::mesh {

struct EngineStats {
  size_t collapses = 0;
  size_t rejectedTopology = 0, rejectedFlip = 0, rejectedSliver = 0;
  double maxErrorSq = 0.0;
  // Where the loop's time goes (profiling): heap tops looked at, of them
  // entries of deleted edges, dirty entries that sank, edges left for a
  // later level (a vertex beside them not this engine's), entries
  // pushed by collapses, compactions.
  size_t tops = 0, deletedTops = 0, sank = 0, notOurs = 0, pushed = 0, compactions = 0;
  size_t evaluations = 0;  // cost evaluations (seeding, tops, re-queued edges)
};

class CollapseEngine {
 public:
  // A queue entry. Key and edge packed in one integer: a non-negative float's bits order
  // like the float, so one unsigned compare orders by key and then by edge
  // (a deterministic tie-break), which keeps the heap's inner loop short.
  struct Entry {
    uint64_t packed = 0;
    static Entry make(float key, uint32_t edge) {
      uint32_t bits;
      const float k = key > 0.0f ? key : 0.0f;  // no -0.0 or NaN bit patterns
      std::memcpy(&bits, &k, 4);
      return {(uint64_t(bits) << 32) | edge};
    }
    float key() const {
      const uint32_t bits = uint32_t(packed >> 32);
      float k;
      std::memcpy(&k, &bits, 4);
      return k;
    }
    uint32_t edge() const { return uint32_t(packed); }
  };
  using EntryVector = LargeVector<Entry>;
  // region: the region of `level` this engine may touch (a vertex is its
  // region's when vd[].region >> level equals it, region_levels.h), or
  // kSharedRegion for all.
  CollapseEngine(DecimationState& state, uint16_t region, unsigned level = 0);

  // Queues `taken` (entries another engine queued, taken over as they are)
  // and the edges of [begin, end) that are neither queued nor deleted and
  // that this engine may collapse.
  void seedRange(uint32_t begin, uint32_t end, EntryVector&& taken = {});
  // Appends to `out` the entries of the edges of [begin, end) that are
  // neither queued nor deleted (clearing their state bytes); returns how
  // many it evaluated. Reads only: workers may share one engine.
  size_t evaluateUnqueued(uint32_t begin, uint32_t end, EntryVector& out) const;
  void countEvaluations(size_t n) { stats_.evaluations += n; }
  // Queues `taken` and the edges of the faces around `vertices` (this
  // engine's) that are neither queued nor deleted and that it may collapse.
  // keyLimit: the limit of the round that follows, known in advance: the
  // queue is split there at once (only the entries up to it are heapified).
  void seedAround(std::span<const uint32_t> vertices, EntryVector&& taken, float keyLimit = HUGE_VALF);
  // Per edge in DecimationState::estate: queued in a heap, its key stale,
  // deleted by a collapse. The deleted bit repeats OpenMesh's edge status
  // so that a heap top costs one byte's load, not that and a status word
  // in another array (the top's status was 40% of the loop's own samples).
  static constexpr uint8_t kQueued = 1, kDirty = 2, kGone = 4;
  static constexpr uint8_t kSeen = 8;  // seedAround's mark, cleared before it returns
  // Queues prepared entries. With heapTarget set and many more entries
  // than that, only about the heapTarget cheapest go into the heap and the
  // rest wait beside it until the heap's top passes them (then those up to
  // the round's limit move in): the same order of collapses as one heap,
  // but the sifts stay in a heap that fits the cache (the last region of a
  // 5M-triangle mesh queues millions of edges and collapses a few per cent
  // of them). run() splits the same way at its round's limit.
  void seedEntries(EntryVector&& entries, size_t heapTarget = SIZE_MAX);
  // Hands the queued entries whose edges are still alive to `out`, dirty
  // ones with their stale keys (re-evaluated when they reach the top, as in
  // this engine): the engine of the next level takes them over instead of
  // evaluating those edges again. This engine's own heap becomes `out` when
  // `out` is empty (no copy); its queue is empty afterwards.
  void takeLiveEntries(EntryVector& out);
  // Evaluates one edge into an entry; false if it cannot collapse at all.
  bool entryFor(uint32_t edge, Entry& out) const;

  // Collapses until `liveFaces` <= targetFaces, the queue is empty, or the
  // cheapest collapse left has a key above keyLimit. `done` counts collapses
  // across engines (progress); only the reporter calls the progress
  // callback. Returns false if cancelled.
  bool run(size_t& liveFaces, size_t targetFaces, float keyLimit, const Progress* progress,
           std::atomic<size_t>& done, size_t expectedTotal, bool reporter);

  // Every `stride`-th key in the queue (for choosing a shared threshold).
  void sampleKeys(size_t stride, std::vector<float>& out) const;
  size_t queued() const { return heap_.size() + rest_.size(); }
  // Whether the last run() stopped at its face target (not at keyLimit or
  // an empty queue): such a queue still holds keys below the limit that
  // this round was not allowed to take.
  bool stoppedAtTarget() const { return stoppedAtTarget_; }

  const EngineStats& stats() const { return stats_; }

 private:
  struct Plan {
    OpenMesh::HalfedgeHandle h;  // from the vertex that goes to the one that stays
    glm::dvec3 p{0.0};           // where the staying vertex ends up
    double errSq = 0.0;
    float key = 0.0f;
    bool moves = false;          // p is an optimal placement (both ends free)
  };
  bool evaluate(uint32_t edge, Plan& plan) const;
  void prefetchNext() const;
  EdgeKind edgeKind(OpenMesh::HalfedgeHandle h) const;
  bool mayTouch(OpenMesh::VertexHandle v) const {
    if (region_ == kSharedRegion) return true;
    const uint16_t r = s_.vd[size_t(v.idx())].region;
    return r != kSharedRegion && (r >> level_) == region_;
  }
  bool topologyOk(const Plan& plan);
  bool geometryOk(const Plan& plan);
  bool wedgeMap(const Plan& plan, uint32_t (&from)[2], uint32_t (&to)[2], int& count) const;
  glm::vec2 interpolateUv(const Plan& plan) const;
  void collapse(const Plan& plan, const uint32_t (&from)[2], const uint32_t (&to)[2], int count,
                size_t& liveFaces);
  void halfedgeCollapse(OpenMesh::HalfedgeHandle h);
  void collapseLoop(OpenMesh::HalfedgeHandle h, bool firstOnBoundary, bool secondOnBoundary);
  void adjustOutgoing(OpenMesh::VertexHandle v);
  void push(const Entry& e);
  void compact();
  void siftDown(size_t i);
  void siftUp(size_t i);
  void removeTop();  // the heap without its top; the edge's state untouched
  void popTop();     // removeTop, and the edge no longer queued
  void adopt(EntryVector&& entries);  // the queue becomes `entries`, not yet ordered
  void splitAt(uint64_t bound);
  void heapify();

  DecimationState& s_;
  DecimationMesh& m_;
  uint16_t region_;
  unsigned level_;
  EntryVector heap_;
  EntryVector rest_;             // entries above restAbove_, not yet in the heap (unsorted)
  EntryVector scratch_;          // splitAt's
  uint64_t restAbove_ = UINT64_MAX;
  // Queues smaller than this are not split (the split's passes would cost
  // more than the sifts they save).
  static constexpr size_t kSplitMin = 4096;
  std::vector<int> ring_;  // scratch for the link condition
  size_t tombstones_ = 0;  // queued entries of deleted edges
  bool stoppedAtTarget_ = false;
  EngineStats stats_;
};

}  // namespace hs::mesh
