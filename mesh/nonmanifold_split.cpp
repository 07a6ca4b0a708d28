#include "mesh/nonmanifold_split.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>

#include "core/parallel.h"

namespace hs::mesh {
namespace {

bool validFace(std::span<const uint32_t> tris, size_t f, uint32_t nv) {
  const uint32_t a = tris[f * 3], b = tris[f * 3 + 1], c = tris[f * 3 + 2];
  return a < nv && b < nv && c < nv && a != b && b != c && a != c;
}

// Outgoing corners of every vertex, each entry packed as (to << 32 | corner)
// so scanning a vertex's list needs no lookup into the triangle array.
struct OutgoingLists {
  UninitArray<uint32_t> offset;  // vertexCount + 1
  UninitArray<uint64_t> entry;
  std::span<const uint64_t> of(uint32_t v) const {
    return {entry.data() + offset[v], entry.data() + offset[v + 1]};
  }
};

// In parallel without atomics: each worker owns a contiguous range of
// vertex ids and scans every corner, counting and filling only the lists
// of its own vertices. Lists come out in corner order, as one serial pass
// would write them, for any number of workers. (Vertices are numbered by
// first use in the decimator, so a worker's writes stay mostly in its part
// of the arrays; the extra cost is each worker reading all corners, which
// is a sequential stream.)
OutgoingLists buildOutgoing(std::span<const uint32_t> tris, uint32_t nv, unsigned threads) {
  OutgoingLists l;
  l.offset.reset(size_t(nv) + 1);
  const size_t nf = tris.size() / 3;
  const unsigned parts = unsigned(std::clamp<size_t>(size_t(nv) / 65536, 1, resolveThreads(threads)));
  auto partBegin = [&](size_t p) { return uint32_t(size_t(nv) * p / parts); };
  auto forOwnCorners = [&](size_t p, auto&& fn) {
    const uint32_t lo = partBegin(p), hi = partBegin(p + 1);
    for (size_t f = 0; f < nf; ++f) {
      if (!validFace(tris, f, nv)) continue;
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t c = uint32_t(f * 3 + k), v = tris[c];
        if (v >= lo && v < hi) fn(v, c);
      }
    }
  };
  parallelTasks(parts, parts, [&](size_t p, unsigned) {
    const uint32_t lo = partBegin(p), hi = partBegin(p + 1);
    std::fill(l.offset.begin() + lo + 1, l.offset.begin() + hi + 1, 0u);
    forOwnCorners(p, [&](uint32_t v, uint32_t) { ++l.offset[v + 1]; });
  });
  l.offset[0] = 0;
  for (size_t v = 0; v < nv; ++v) l.offset[v + 1] += l.offset[v];
  l.entry.reset(l.offset[nv]);
  UninitArray<uint32_t> cursor(nv);
  parallelTasks(parts, parts, [&](size_t p, unsigned) {
    std::copy(l.offset.begin() + partBegin(p), l.offset.begin() + partBegin(p + 1), cursor.begin() + partBegin(p));
    forOwnCorners(p, [&](uint32_t v, uint32_t c) {
      l.entry[cursor[v]++] = (uint64_t(tris[nextCorner(c)]) << 32) | c;
    });
  });
  return l;
}

inline uint32_t entryTo(uint64_t e) { return uint32_t(e >> 32); }
inline uint32_t entryCorner(uint64_t e) { return uint32_t(e); }

struct EdgeCorners {
  uint32_t same = 0, opposite = 0;  // corners a->b and b->a
  uint32_t oppositeCorner = kNoCorner;
  uint32_t minCorner = kNoCorner;
};

EdgeCorners edgeCorners(const OutgoingLists& l, uint32_t a, uint32_t b) {
  EdgeCorners e;
  for (uint64_t x : l.of(a))
    if (entryTo(x) == b) ++e.same, e.minCorner = std::min(e.minCorner, entryCorner(x));
  for (uint64_t x : l.of(b))
    if (entryTo(x) == a) {
      ++e.opposite;
      e.oppositeCorner = entryCorner(x);
      e.minCorner = std::min(e.minCorner, entryCorner(x));
    }
  return e;
}

// What splitNonManifold has to look at: the lowest corner of each
// non-manifold edge and the bow-tie vertices (not on such an edge), each
// sorted. Empty on a manifold mesh.
struct Defects {
  std::vector<uint32_t> edgeCorners, bowTies;
};

// Per-worker lists joined and sorted, so the result does not depend on the
// number of workers.
struct PerWorkerLists {
  std::vector<std::vector<uint32_t>> lists;
  explicit PerWorkerLists(unsigned threads) : lists(std::max(1u, resolveThreads(threads))) {}
  std::vector<uint32_t> joined() const {
    std::vector<uint32_t> all;
    for (const auto& l : lists) all.insert(all.end(), l.begin(), l.end());
    std::sort(all.begin(), all.end());
    return all;
  }
};

// Corners reached from `start` (a corner leaving a vertex with k corners)
// by walking through twins around the vertex, both ways when the fan is
// open; fewer than k means the vertex's faces form more than one fan.
size_t fanSize(std::span<const uint32_t> twin, uint32_t start, size_t k) {
  size_t count = 1;
  bool closed = false;
  for (uint32_t c = start; count <= k;) {
    const uint32_t n = twin[prevCorner(c)];
    if (n == kNoCorner) break;
    if (n == start) {
      closed = true;
      break;
    }
    ++count;
    c = n;
  }
  if (!closed)
    for (uint32_t c = start; count <= k;) {
      const uint32_t tw = twin[c];
      if (tw == kNoCorner) break;
      c = nextCorner(tw);
      ++count;
    }
  return count;
}

CornerTopology analyze(std::span<const uint32_t> tris, uint32_t nv, const OutgoingLists& l, unsigned threads,
                       Defects* defects = nullptr) {
  CornerTopology t;
  PerWorkerLists edgeLists(threads), bowTieLists(threads);
  t.twin.reset(tris.size());
  parallelFill(t.twin.begin(), tris.size(), kNoCorner, threads);
  std::atomic<size_t> nmEdges{0}, boundary{0}, nmVertices{0};
  // Twins: every vertex resolves its own outgoing corners, so the writes of
  // different workers never touch the same corner.
  parallelRanges(nv, threads, [&](size_t begin, size_t end, unsigned w) {
    size_t nm = 0, open = 0;
    for (size_t a = begin; a < end; ++a) {
      const auto la = l.of(uint32_t(a));
      // Does a's list name any vertex twice? A 64-bit mask of the ids' low
      // bits answers "certainly not" in one pass for almost every vertex.
      uint64_t mask = 0;
      bool maybeRepeats = false;
      for (uint64_t x : la) {
        const uint64_t bit = uint64_t(1) << (entryTo(x) & 63);
        maybeRepeats |= (mask & bit) != 0;
        mask |= bit;
      }
      for (size_t i = 0; i < la.size(); ++i) {
        const uint32_t b = entryTo(la[i]), c = entryCorner(la[i]);
        // The common case first: b's list holds exactly one corner back to
        // a, and a's list no other corner to b.
        uint32_t back = kNoCorner, backs = 0;
        for (uint64_t y : l.of(b))
          if (entryTo(y) == uint32_t(a)) back = entryCorner(y), ++backs;
        bool repeated = false;
        if (maybeRepeats)
          for (size_t j = 0; j < la.size(); ++j) repeated |= j != i && entryTo(la[j]) == b;
        if (!repeated && backs == 1) {
          t.twin[c] = back;
          continue;
        }
        if (!repeated && backs == 0) {
          ++open;
          continue;
        }
        if (c == edgeCorners(l, uint32_t(a), b).minCorner) {  // counted once, by the edge's lowest corner
          ++nm;
          if (defects) edgeLists.lists[w].push_back(c);
        }
      }
    }
    nmEdges += nm;
    boundary += open;
  });
  // Fans: walk around each vertex through twins; fewer faces reached than
  // the vertex has means its faces form more than one fan. Vertices on a
  // non-manifold edge are split by that edge already and not counted again.
  auto onNonManifoldEdge = [&](uint32_t c) {
    if (t.twin[c] != kNoCorner) return false;
    const EdgeCorners e = edgeCorners(l, tris[c], tris[nextCorner(c)]);
    return !(e.same == 1 && e.opposite == 0);
  };
  parallelRanges(nv, threads, [&](size_t begin, size_t end, unsigned w) {
    size_t nm = 0;
    for (size_t v = begin; v < end; ++v) {
      const auto list = l.of(uint32_t(v));
      const size_t k = list.size();
      if (k < 2) continue;
      bool touchesNonManifold = false;
      for (uint64_t x : list)
        if (onNonManifoldEdge(entryCorner(x)) || onNonManifoldEdge(prevCorner(entryCorner(x)))) {
          touchesNonManifold = true;
          break;
        }
      if (touchesNonManifold) continue;
      if (fanSize({t.twin.data(), t.twin.size()}, entryCorner(list[0]), k) < k) {
        ++nm;
        if (defects) bowTieLists.lists[w].push_back(uint32_t(v));
      }
    }
    nmVertices += nm;
  });
  t.nonManifoldEdges = nmEdges;
  t.boundaryEdges = boundary;
  t.nonManifoldVertices = nmVertices;
  if (defects) defects->edgeCorners = edgeLists.joined(), defects->bowTies = bowTieLists.joined();
  return t;
}

// Union-find over a sorted list of corners (the corners of the vertices
// being split); the smaller index becomes the root so the result does not
// depend on the order unions happen in.
struct CornerSets {
  std::span<const uint32_t> corners;  // sorted
  std::vector<uint32_t> parent;       // local indices
  explicit CornerSets(std::span<const uint32_t> sorted) : corners(sorted), parent(sorted.size()) {
    for (size_t i = 0; i < parent.size(); ++i) parent[i] = uint32_t(i);
  }
  uint32_t local(uint32_t corner) const {
    return uint32_t(std::lower_bound(corners.begin(), corners.end(), corner) - corners.begin());
  }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a == b) return;
    if (a < b)
      parent[b] = a;
    else
      parent[a] = b;
  }
};

// After a split, is the mesh manifold now? Decided on the corners whose
// edge has a rewritten end: `rewritten` (sorted) holds every corner of
// every split vertex, so it holds every corner that now names a split
// vertex or one of its copies, and their previous corners are the edges
// coming into them. Every edge whose twins can differ from this round's
// analysis has such an end (the defects' edges and fans all do), so a
// whole-mesh analysis of the result would agree with this round's
// everywhere else. On true, `topology` is the result's (twins of those
// corners rewritten, counts set); on false its twins are part-written and
// the caller analyses the whole mesh. Only for meshes whose faces are all
// valid: a face that repeats an id becomes a face when its corners get
// copies, which a fresh analysis counts and this one would not.
bool manifoldAfterSplit(std::span<const uint32_t> tris, std::span<const uint32_t> rewritten,
                        const OutgoingLists& before, uint32_t nvBefore, CornerTopology& topology,
                        unsigned threads) {
  std::vector<uint32_t> near;
  near.reserve(rewritten.size() * 2);
  for (const uint32_t c : rewritten) near.push_back(c), near.push_back(prevCorner(c));
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
  std::vector<std::pair<uint64_t, uint32_t>> edges;  // (a -> b, corner), sorted
  edges.reserve(near.size());
  for (const uint32_t c : near) edges.push_back({key(tris[c], tris[nextCorner(c)]), c});
  std::sort(edges.begin(), edges.end());
  auto range = [&](uint64_t k) {
    return std::equal_range(edges.begin(), edges.end(), std::pair<uint64_t, uint32_t>{k, 0},
                            [](const auto& x, const auto& y) { return x.first < y.first; });
  };
  UninitArray<uint32_t>& twin = topology.twin;
  for (const uint32_t c : near) {
    const uint32_t a = tris[c], b = tris[nextCorner(c)];
    const auto same = range(key(a, b)), back = range(key(b, a));
    if (same.second - same.first != 1 || back.second - back.first > 1) return false;  // a non-manifold edge
    twin[c] = back.first == back.second ? kNoCorner : back.first->second;
  }
  // One fan per vertex at either end of those edges (the others' corners
  // and twins are as the round's analysis found them: one fan each). No
  // test mesh has reached this with a bow-tie left: a fan the round could
  // not separate kept a non-manifold edge, refused above. It is checked
  // all the same, so that the answer never rests on that.
  std::vector<uint32_t> ends;
  for (const uint32_t c : near) ends.push_back(tris[c]), ends.push_back(tris[nextCorner(c)]);
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<std::pair<uint32_t, uint32_t>> copyCorners;  // (copy id, corner): the copies' corners
  for (const uint32_t c : rewritten)
    if (tris[c] >= nvBefore) copyCorners.push_back({tris[c], c});
  std::sort(copyCorners.begin(), copyCorners.end());
  std::vector<uint32_t> fan;
  for (const uint32_t v : ends) {
    fan.clear();
    if (v < nvBefore) {  // an id kept: its corners are some of those it had
      for (const uint64_t x : before.of(v))
        if (tris[entryCorner(x)] == v) fan.push_back(entryCorner(x));
    } else {
      auto it = std::lower_bound(copyCorners.begin(), copyCorners.end(), std::pair<uint32_t, uint32_t>{v, 0});
      for (; it != copyCorners.end() && it->first == v; ++it) fan.push_back(it->second);
    }
    const size_t k = fan.size();
    if (k < 2) continue;
    if (fanSize({twin.data(), twin.size()}, fan[0], k) < k) return false;  // still a bow-tie
  }
  std::atomic<size_t> open{0};
  parallelRanges(twin.size(), threads, [&](size_t b, size_t e, unsigned) {
    size_t n = 0;
    for (size_t c = b; c < e; ++c) n += twin[c] == kNoCorner;
    open += n;
  });
  topology.boundaryEdges = open;
  topology.nonManifoldEdges = topology.nonManifoldVertices = 0;
  return true;
}

}  // namespace

CornerTopology analyzeCorners(std::span<const uint32_t> tris, uint32_t vertexCount, unsigned threads) {
  const OutgoingLists l = buildOutgoing(tris, vertexCount, threads);
  return analyze(tris, vertexCount, l, threads);
}

NonManifoldSplitStats splitNonManifold(std::span<uint32_t> tris, uint32_t vertexCount,
                                       std::vector<uint32_t>& copiedFrom, CornerTopology& topology,
                                       unsigned threads) {
  NonManifoldSplitStats stats;
  const uint32_t originalCount = vertexCount;
  uint32_t nv = vertexCount;
  const size_t nc = tris.size();
  // Round 0 pairs the faces of each non-manifold edge and splits every vertex
  // into its fans. A face left unpaired can still hang on both ends of its
  // edge through other faces (a fin glued along a fold); round 1 detaches
  // such faces completely, and round 2 splits the fans that leaves behind.
  //
  // Only the vertices next to a defect can change: every other vertex has
  // one fan, whose corners all join through their twins, so it keeps its
  // id. The work below is limited to those vertices' corners; the passes
  // over the whole mesh are the (parallel) analysis and one parallel scan
  // for the corners. (A real scan has a few hundred defects among
  // millions of faces; a union-find over every corner was a serial pass
  // of 15 ms on a 65k-triangle mesh.) The result is the same as joining
  // the fans of every vertex. Whether a round left the mesh manifold is
  // checked on the rewritten corners too (manifoldAfterSplit); only when
  // it did not does the next round analyse the whole mesh again.
  for (int round = 0; round < 4; ++round) {
    const OutgoingLists l = buildOutgoing(tris, nv, threads);
    Defects defects;
    topology = analyze(tris, nv, l, threads, &defects);
    ++stats.wholeMeshAnalyses;
    if (round == 0) {
      stats.nonManifoldEdges = topology.nonManifoldEdges;
      stats.nonManifoldVertices = topology.nonManifoldVertices;
    }
    if (topology.manifold() || round == 3) break;

    // The next round analyses again, so the twins are this round's to edit.
    UninitArray<uint32_t>& twin = topology.twin;
    std::vector<uint32_t> touched = defects.bowTies;  // vertices to split into their fans
    std::vector<uint32_t> detachedFaces;
    for (const uint32_t first : defects.edgeCorners) {
      const uint32_t a = tris[first], b = tris[nextCorner(first)];
      touched.push_back(a), touched.push_back(b);
      // All corners of this non-manifold edge, both directions, by index.
      std::vector<std::pair<uint32_t, bool>> corners;  // (corner, runs a->b)
      for (uint64_t y : l.of(a))
        if (entryTo(y) == b) corners.push_back({entryCorner(y), true});
      for (uint64_t y : l.of(b))
        if (entryTo(y) == a) corners.push_back({entryCorner(y), false});
      std::sort(corners.begin(), corners.end());
      std::vector<uint8_t> paired(corners.size(), 0);
      bool firstPairMade = false;
      // Which faces to pair: those that sit firmly in the surface, so that
      // the defect (a fin, a sliver, a loose copy) is what comes off, not
      // a face of the surface. Pairs are taken best first:
      // * a face and its copy the other way round (a back face on the same
      //   three vertices) only when nothing else is left: paired so, the
      //   face left the surface with its copy and decimated results had a
      //   hole where it had been;
      // * then by how many of the two faces' other edges have a twin (a
      //   fin's or a sliver's have none): paired by corner order, a sliver
      //   fin that came first took a surface face's place and the face was
      //   detached in the next round, leaving a hole that decimation
      //   opened into a crack (test_meshproc_decimate::meshesWithRandomDefectsDecimate);
      // * then by corner order (deterministic).
      auto sameVertices = [&](uint32_t c, uint32_t d) {
        std::array<uint32_t, 3> x{tris[c / 3 * 3], tris[c / 3 * 3 + 1], tris[c / 3 * 3 + 2]},
            y{tris[d / 3 * 3], tris[d / 3 * 3 + 1], tris[d / 3 * 3 + 2]};
        std::sort(x.begin(), x.end()), std::sort(y.begin(), y.end());
        return x == y;
      };
      auto anchoring = [&](uint32_t c) {
        return int(twin[nextCorner(c)] != kNoCorner) + int(twin[prevCorner(c)] != kNoCorner);
      };
      struct Candidate {
        bool copies;
        int anchoring;
        uint32_t i, j;
      };
      std::vector<Candidate> candidates;
      for (uint32_t i = 0; i < corners.size(); ++i)
        for (uint32_t j = i + 1; j < corners.size(); ++j)
          if (corners[j].second != corners[i].second)
            candidates.push_back({sameVertices(corners[i].first, corners[j].first),
                                  anchoring(corners[i].first) + anchoring(corners[j].first), i, j});
      std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
        if (x.copies != y.copies) return !x.copies;
        if (x.anchoring != y.anchoring) return x.anchoring > y.anchoring;
        return std::pair(x.i, x.j) < std::pair(y.i, y.j);
      });
      for (const Candidate& p : candidates) {
        if (paired[p.i] || paired[p.j]) continue;
        if (round > 0 && firstPairMade) break;
        twin[corners[p.i].first] = corners[p.j].first;
        twin[corners[p.j].first] = corners[p.i].first;
        paired[p.i] = paired[p.j] = 1;
        firstPairMade = true;
      }
      if (round > 0)
        for (size_t i = 0; i < corners.size(); ++i) {
          // Without any pair the first face keeps the edge as its boundary.
          if (paired[i] || (!firstPairMade && i == 0)) continue;
          detachedFaces.push_back(corners[i].first / 3);
        }
    }
    std::sort(detachedFaces.begin(), detachedFaces.end());
    detachedFaces.erase(std::unique(detachedFaces.begin(), detachedFaces.end()), detachedFaces.end());
    for (const uint32_t f : detachedFaces)
      for (uint32_t k = 0; k < 3; ++k)
        if (tris[f * 3 + k] < nv) touched.push_back(tris[f * 3 + k]);
    stats.facesDetached += detachedFaces.size();
    auto isDetached = [&](uint32_t c) { return std::binary_search(detachedFaces.begin(), detachedFaces.end(), c / 3); };

    // A face that repeats an id (or names one past the end) joins no fan:
    // its vertices are split too, its corners getting copies of their own.
    PerWorkerLists invalidLists(threads);
    parallelRanges(nc / 3, threads, [&](size_t b, size_t e, unsigned w) {
      for (size_t f = b; f < e; ++f)
        if (!validFace(tris, f, nv))
          for (uint32_t k = 0; k < 3; ++k)
            if (tris[f * 3 + k] < nv) invalidLists.lists[w].push_back(tris[f * 3 + k]);
    });
    bool allFacesValid = true;
    for (const auto& list : invalidLists.lists) {
      touched.insert(touched.end(), list.begin(), list.end());
      allFacesValid &= list.empty();
    }

    // Every corner of a touched vertex, in corner order.
    std::vector<uint8_t> isTouched(nv, 0);
    for (const uint32_t v : touched) isTouched[v] = 1;
    const std::vector<uint32_t> corners =
        keptIndices(nc, threads, [&](size_t c) { return tris[c] < nv && isTouched[tris[c]]; });

    // Two corners leaving one vertex share its fan when one's edge is
    // twinned with the edge coming back into the vertex before the other.
    CornerSets sets(corners);
    for (uint32_t i = 0; i < corners.size(); ++i) {
      const uint32_t c = corners[i], t = twin[c];
      if (t == kNoCorner || isDetached(c) || isDetached(t)) continue;
      sets.unite(i, sets.local(nextCorner(t)));  // both leave tris[c]
    }
    std::vector<uint32_t> idOfRoot(corners.size(), UINT32_MAX);
    std::vector<uint8_t> claimed(nv, 0);
    for (uint32_t i = 0; i < corners.size(); ++i) {
      const uint32_t c = corners[i], v = tris[c], r = sets.find(i);
      if (idOfRoot[r] == UINT32_MAX) {
        if (!claimed[v]) {
          claimed[v] = 1;
          idOfRoot[r] = v;
        } else {
          idOfRoot[r] = originalCount + uint32_t(copiedFrom.size());
          copiedFrom.push_back(v < originalCount ? v : copiedFrom[v - originalCount]);
        }
      }
      tris[c] = idOfRoot[r];
    }
    const uint32_t nvBefore = nv;
    nv = originalCount + uint32_t(copiedFrom.size());
    // Usually one split leaves the mesh manifold; confirming that where the
    // split wrote spares a second analysis of the whole mesh.
    if (allFacesValid && manifoldAfterSplit(tris, corners, l, nvBefore, topology, threads)) break;
  }
  stats.verticesAdded = nv - originalCount;
  return stats;
}

}  // namespace hs::mesh
