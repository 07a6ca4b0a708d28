#include "meshproc/region_levels.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/parallel.h"

namespace hs::mesh {
namespace {

using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;
using Entry = CollapseEngine::Entry;
using EntryVector = CollapseEngine::EntryVector;
using Engines = std::vector<std::unique_ptr<CollapseEngine>>;

// A region only removes vertices whose faces are all its own, so a strip
// along its border stays at full resolution until a level where both sides
// of it belong to one region. A level's rounds stop with its strips' share
// of the work left, and never take a region below kMinFacesPerRegion:
// regions decimated to a handful of large triangles would meet the dense
// strips in long slivers that no later collapse can repair (measured: 1%
// on the bunny with 4 regions had a Hausdorff of 4.2% of the diagonal
// without this floor, 1.0% with it).
constexpr size_t kMinFacesPerRegion = 3000;

// What each level's rounds leave to the next beyond the strips: one
// percent of the faces; a quarter of that on large meshes when the target
// keeps a quarter or more. Late rounds would each remove a few faces for
// the cost of a synchronisation, and where the regions are held at their
// floors they stop at proportional shares instead of one error level: at
// 1% on the 5M scan tile, half a percent gave 1.9x the Hausdorff, a
// quarter 6x (with 64 regions and one serial pass after them).
size_t slackFor(size_t target, size_t nf) { return target * 4 >= nf && nf >= 1000000 ? nf / 400 : nf / 100; }

// The regions of every level. Level 0 has `regions0` regions, each an
// equal run of the Morton-ordered faces; level L merges runs of 2^L of
// them; the top level is one region.
struct Levels {
  size_t nf = 0, regions0 = 1;
  unsigned top = 0;
  std::vector<size_t> edgeStart;  // per level-0 region: its first edge (edge ids follow faces)

  size_t regionsAt(unsigned level) const { return (regions0 + (size_t(1) << level) - 1) >> level; }
  size_t firstOriginal(unsigned level, size_t r) const { return std::min(regions0, r << level); }
  // Face f is in level-0 region f * regions0 / nf (the setup's rule); its
  // run starts at the first face that rule puts there.
  size_t faceBegin(unsigned level, size_t r) const {
    const size_t o = firstOriginal(level, r);
    return (o * nf + regions0 - 1) / regions0;
  }
  size_t edgeBegin(unsigned level, size_t r) const { return edgeStart[firstOriginal(level, r)]; }
  uint16_t originalOf(size_t f) const { return uint16_t(f * regions0 / nf); }
};

Levels makeLevels(const DecimationState& st, size_t regions0) {
  Levels lv;
  const auto& m = st.mesh;
  lv.nf = m.n_faces();
  lv.regions0 = regions0;
  while (lv.regionsAt(lv.top) > 1) ++lv.top;
  // An edge inside a region has both faces there, so the face of its first
  // halfedge (the lower-numbered face, by the builder's numbering) is in the
  // region's run: bisect for each run's edges. Done before any collapse,
  // which rewires halfedges to other faces (of the same region).
  const size_t ne = m.n_edges();
  lv.edgeStart.resize(regions0 + 1);
  for (size_t r = 0; r <= regions0; ++r) {
    if (r == regions0) {
      lv.edgeStart[r] = ne;
      continue;
    }
    const int fb = int(lv.faceBegin(0, r));
    size_t lo = 0, hi = ne;
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      if (m.face_handle(HalfedgeHandle{int(2 * mid)}).idx() < fb) lo = mid + 1;
      else hi = mid;
    }
    lv.edgeStart[r] = lo;
  }
  return lv;
}

// Vertices still shared at `level` whose faces now all lie in one region of
// it become that region's: their region is set to the level-0 region of one
// of their faces (CollapseEngine::mayTouch compares it shifted by the
// level). `shared` keeps those still shared; the claimed ones are returned
// grouped by their region at this level, each group in id order.
std::vector<std::vector<uint32_t>> claimAtLevel(DecimationState& st, const Levels& lv, unsigned level,
                                                std::vector<uint32_t>& shared, unsigned threads) {
  const auto& m = st.mesh;
  const unsigned workers = std::max(1u, threads);
  std::vector<std::vector<uint32_t>> still(workers), claimed(workers);
  parallelRanges(shared.size(), workers, [&](size_t b, size_t e, unsigned w) {
    for (size_t i = b; i < e; ++i) {
      const uint32_t v = shared[i];
      const HalfedgeHandle start = m.halfedge_handle(VertexHandle(int(v)));
      uint16_t first = kSharedRegion;
      bool one = start.is_valid();
      HalfedgeHandle it = start;
      if (one) do {
          const FaceHandle f = m.face_handle(it);
          if (f.is_valid()) {
            const uint16_t r = lv.originalOf(size_t(f.idx()));
            if (first == kSharedRegion) first = r;
            else if ((r >> level) != (first >> level)) one = false;
          }
          it = m.next_halfedge_handle(m.opposite_halfedge_handle(it));
        } while (one && it != start);
      if (one && first != kSharedRegion) {
        st.vd[v].region = first;
        claimed[w].push_back(v);
      } else {
        still[w].push_back(v);
      }
    }
  }, 1024);
  shared.clear();
  for (const auto& x : still) shared.insert(shared.end(), x.begin(), x.end());
  std::vector<std::vector<uint32_t>> byRegion(lv.regionsAt(level));
  for (const auto& x : claimed)
    for (uint32_t v : x) byRegion[size_t(st.vd[v].region >> level)].push_back(v);
  return byRegion;
}

std::vector<uint32_t> sharedVertices(const DecimationState& st, unsigned threads) {
  const size_t nv = st.vd.size();
  const unsigned workers = std::max(1u, threads);
  std::vector<std::vector<uint32_t>> part(workers);
  parallelRanges(nv, workers, [&](size_t b, size_t e, unsigned w) {
    for (size_t v = b; v < e; ++v)
      if (st.vd[v].region == kSharedRegion && st.mesh.halfedge_handle(VertexHandle(int(v))).is_valid())
        part[w].push_back(uint32_t(v));
  });
  std::vector<uint32_t> all;
  for (const auto& p : part) all.insert(all.end(), p.begin(), p.end());
  return all;
}

EngineStats sumStats(const Engines& engines) {
  EngineStats sum;
  for (const auto& e : engines) {
    if (!e) continue;
    const EngineStats& x = e->stats();
    sum.collapses += x.collapses, sum.tops += x.tops, sum.deletedTops += x.deletedTops, sum.sank += x.sank;
    sum.notOurs += x.notOurs, sum.pushed += x.pushed, sum.compactions += x.compactions;
    sum.evaluations += x.evaluations;
    sum.rejectedTopology += x.rejectedTopology, sum.rejectedFlip += x.rejectedFlip, sum.rejectedSliver += x.rejectedSliver;
  }
  return sum;
}

}  // namespace

ScheduleResult runRegionLevels(DecimationState& st, size_t regions0, size_t target, unsigned threads,
                               const Progress* progress, DecimateTrace* trace) {
  const auto t0 = DecimateClock::now();
  ScheduleResult res;
  auto& m = st.mesh;
  const size_t nf = m.n_faces();
  const bool countTarget = target > 0;
  const Levels lv = makeLevels(st, regions0);
  const size_t slack = slackFor(target, nf);
  std::atomic<size_t> done{0};
  const size_t expected = nf > target ? (nf - target) / 2 : 0;
  std::atomic<bool> cancelled{false};
  auto mark = [&](const char* what) {
    if (trace) trace->mark(what);
  };
  const bool traceOn = trace && trace->on, traceRounds = trace && trace->rounds;

  std::vector<uint32_t> shared = lv.top > 0 ? sharedVertices(st, threads) : std::vector<uint32_t>();
  Engines engines;
  res.liveFaces = nf;
  std::vector<size_t> prevLive;   // live faces per region of the level before
  float level0Limit = HUGE_VALF;  // the last threshold of level 0's rounds
  bool level0Ran = false;
  for (unsigned level = 0; level <= lv.top; ++level) {
    const size_t regions = lv.regionsAt(level);
    const bool last = level == lv.top;
    const std::vector<std::vector<uint32_t>> claimed =
        level > 0 ? claimAtLevel(st, lv, level, shared, threads) : std::vector<std::vector<uint32_t>>();
    for (const auto& e : engines)
      if (e) res.stats.push_back(e->stats());

    // The level's engines, one a region: each takes over its two halves'
    // queues as they are (dirty entries with their stale keys, re-evaluated
    // when they reach the top) and evaluates the edges no queue holds: at
    // level 0 all of its run; later those of the faces around the vertices
    // it claimed (the strip between its halves, and edges its halves
    // dropped because a vertex beside them was not theirs); the last region
    // every edge no queue holds (edges refused before get another look:
    // their neighbourhood may allow them now).
    Engines next(regions);
    // A catching-up level's one round has level 0's last threshold: its
    // queues are split there as they are built.
    const float catchUpLimit = level > 0 && countTarget && level0Ran ? level0Limit : HUGE_VALF;
    // Region r's engine and the queues of its halves, whose engines are
    // then done with (each task touches only its own two).
    auto make = [&](size_t r) {
      auto e = std::make_unique<CollapseEngine>(st, last ? kSharedRegion : uint16_t(r), level);
      EntryVector taken;
      if (level > 0)
        for (size_t c = 2 * r; c < std::min(2 * r + 2, engines.size()); ++c) {
          engines[c]->takeLiveEntries(taken);
          engines[c].reset();
        }
      return std::pair(std::move(e), std::move(taken));
    };
    if (!last) {
      parallelTasks(regions, threads, [&](size_t r, unsigned) {
        auto [e, taken] = make(r);
        if (level == 0)
          e->seedRange(uint32_t(lv.edgeBegin(level, r)), uint32_t(lv.edgeBegin(level, r + 1)), std::move(taken));
        else
          e->seedAround(claimed[r], std::move(taken), catchUpLimit);
        next[r] = std::move(e);
      });
    } else {
      // One region: its queue is built from every worker's part (the
      // evaluation is most of the time here), and only about 8x the
      // collapses still to make go into the heap (CollapseEngine::seedEntries).
      auto [e, taken] = make(0);
      std::vector<EntryVector> parts(std::max(1u, threads));
      std::vector<size_t> evaluated(parts.size(), 0);
      parallelRanges(m.n_edges(), unsigned(parts.size()), [&](size_t b, size_t en, unsigned w) {
        evaluated[w] = e->evaluateUnqueued(uint32_t(b), uint32_t(en), parts[w]);
      });
      size_t count = taken.size(), evals = 0;
      for (size_t w = 0; w < parts.size(); ++w) count += parts[w].size(), evals += evaluated[w];
      taken.reserve(count);
      for (auto& p : parts) taken.insert(taken.end(), p.begin(), p.end());
      parts = {};
      e->countEvaluations(evals);
      const size_t toGo = res.liveFaces > target ? (res.liveFaces - target) / 2 : 0;
      e->seedEntries(std::move(taken), std::max<size_t>(65536, 8 * toGo));
      next[0] = std::move(e);
    }
    engines = std::move(next);
    mark(last ? "final: queue" : "level: engines");

    if (last) {
      if (!engines[0]->run(res.liveFaces, target, HUGE_VALF, progress, done, expected, true)) cancelled = true;
      res.stats.push_back(engines[0]->stats());
      res.finalCollapses = engines[0]->stats().collapses;
      if (traceOn) {
        const EngineStats& x = engines[0]->stats();
        std::fprintf(stderr,
                     "  final: evaluated %zu collapses %zu tops %zu deleted %zu sank %zu pushed %zu compactions %zu "
                     "topo %zu flip %zu sliver %zu queued %zu\n",
                     x.evaluations, x.collapses, x.tops, x.deletedTops, x.sank, x.pushed, x.compactions,
                     x.rejectedTopology, x.rejectedFlip, x.rejectedSliver, engines[0]->queued());
      }
      mark("final: run");
      break;
    }

    // Per region: its live faces (at level 0 counted, later its halves'
    // counts), and at level 0 those on its strip (touching a shared
    // vertex), which wait for a later level.
    std::vector<size_t> live(regions, 0);
    size_t stopAt = target;
    if (level == 0) {
      std::vector<size_t> stripOf(regions, 0);
      parallelTasks(regions, threads, [&](size_t r, unsigned) {
        for (size_t f = lv.faceBegin(level, r); f < lv.faceBegin(level, r + 1); ++f) {
          if (st.faceStatus[f].deleted()) continue;
          ++live[r];
          for (size_t k = 0; k < 3; ++k)
            if (st.vd[st.fv[f * 3 + k]].region == kSharedRegion) {
              ++stripOf[r];
              break;
            }
        }
      });
      size_t strip = 0, alive = 0;
      for (size_t r = 0; r < regions; ++r) strip += stripOf[r], alive += live[r];
      const double keepShare = alive > 0 ? double(target) / double(alive) : 1.0;
      stopAt = std::max(target + size_t(double(strip) * (1.0 - keepShare)), regions * kMinFacesPerRegion);
      if (traceOn) std::fprintf(stderr, "  level 0: strip %zu faces, stopping at %zu\n", strip, stopAt);
    } else {
      for (size_t r = 0; r < regions; ++r)
        for (size_t c = 2 * r; c < std::min(2 * r + 2, prevLive.size()); ++c) live[r] += prevLive[c];
    }
    auto total = [&] {
      size_t n = 0;
      for (size_t x : live) n += x;
      return n;
    };

    // Rounds: within a round every region runs its own greedy queue up to
    // one threshold, and since regions share no vertex that is what one
    // greedy queue over the whole mesh would do up to that cost, so the
    // triangle budget goes where the surface needs it, not split by region
    // size. Rounds alternate with a serial step (chooseRound) that picks the
    // next threshold from samples of every region's queue; a round is one
    // parallel loop over the regions on the scheduler's pool (no thread is
    // started per round, which cost more than a small mesh's whole round).
    // A round never takes a region below its share of the stopping count,
    // so one round cannot overshoot the target whatever the threshold.
    //
    // Levels after the first run one round each, catching up: the strips
    // their merged halves shared, and regions that level 0's floors held
    // back, go as far as level 0's last threshold, where the rest of the
    // mesh stands. That is the work the next collapses in one greedy order
    // would do first (every key below that threshold comes before any
    // above it), so the last region, which finishes the count in that
    // order, starts where the old single border pass stood after its
    // cheapest collapses. Their floors are shares of the target only: a
    // level's own stopping count would hold regions at proportional shares
    // instead of one error level (measured: 36% more Hausdorff at 1% on
    // the 5M scan tile when every level ran rounds to its own count).
    float limit = level == 0 ? HUGE_VALF : level0Limit;
    const size_t floorCount = level == 0 ? stopAt : target;
    size_t now = total(), roundStart = now;
    unsigned levelRounds = 0;
    bool finished = false;
    double effectiveness = 0.5, wanted = 1.0;
    std::vector<float> keys;
    auto chooseRound = [&] {
      if (level > 0) {
        finished = levelRounds > 0 || cancelled || (countTarget && (!level0Ran || total() <= target));
        if (!finished) ++levelRounds, ++res.rounds;
        now = total();
        return;
      }
      const size_t before = roundStart;
      now = total();
      if (levelRounds > 0) {
        if (now == before || !countTarget) {
          finished = true;  // nothing under the threshold could go, or maxError's single round is done
          return;
        }
        effectiveness = double(before - now) / 2.0 / std::max(1.0, wanted);
      }
      if (cancelled || levelRounds >= 100 || (countTarget && now <= stopAt + slack)) {
        finished = true;
        return;
      }
      if (countTarget) {
        size_t queued = 0;
        for (const auto& e : engines) queued += e->queued();
        if (queued == 0) {
          finished = true;
          return;
        }
        keys.clear();
        const size_t stride = std::max<size_t>(1, queued / 4096);
        // Queues of regions held at their floor last round still hold keys
        // under the old threshold that only the floor kept: sampled, they
        // pinned the threshold where the other regions had nothing left
        // (dozens of rounds removing almost nothing at 50% on the scan
        // tile). The threshold comes from the regions that ran out of keys.
        for (const auto& e : engines)
          if (levelRounds == 0 || !e->stoppedAtTarget()) e->sampleKeys(stride, keys);
        if (keys.empty())
          for (const auto& e : engines) e->sampleKeys(stride, keys);
        const double remaining = double(now - std::min(now, stopAt)) / 2.0;  // collapses
        // Half of what is left, scaled up by how short the last round fell.
        // Larger steps overshoot: regions then stop at their proportional
        // shares instead of at one error level (measured on the scan tile:
        // 0.7 of the rest gave 3x the Hausdorff at 5%). The scale-up may
        // ask for up to 1.6x the rest: stale (dirty) keys below the
        // threshold make a round achieve a fifth or so of what it asks, and
        // a cap of 1x took 20-22 rounds at 1-5% (bunny and scan tile), 1.6x
        // 12-14 with the same Hausdorff on the tile (3% more at 1% on the
        // bunny); 2.5x took 7-9 but had 16% more Hausdorff at 1% on the
        // tile.
        wanted = std::min(1.6 * remaining, 0.5 * remaining / std::max(effectiveness, 0.05));
        if (keys.empty()) {
          finished = true;
          return;
        }
        // Each sample stands for `stride` live entries.
        const size_t k = std::min(keys.size() - 1, size_t(wanted / double(stride)));
        std::nth_element(keys.begin(), keys.begin() + long(k), keys.end());
        limit = keys[k];
      }  // else maxError alone: one round, everything within it, everywhere
      if (traceRounds)
        std::fprintf(stderr, "  level %u round %u: live %zu stopAt %zu eff %.3f wanted %.0f limit %g keys %zu\n", level,
                     levelRounds, now, stopAt, effectiveness, wanted, double(limit), keys.size());
      roundStart = now;
      ++levelRounds;
      ++res.rounds;
      level0Limit = limit;
      level0Ran = true;
    };
    for (chooseRound(); !finished; chooseRound()) {
      const EngineStats before = traceRounds ? sumStats(engines) : EngineStats{};
      const auto roundWall = DecimateClock::now();
      const double roundCpu = traceRounds ? processCpuNow() : 0.0;
      std::vector<double> regionCpu(traceRounds ? regions : 0, 0.0);
      parallelTasks(regions, threads, [&](size_t r, unsigned slot) {
        const size_t floor =
            countTarget ? size_t(std::ceil(double(live[r]) * double(floorCount) / double(std::max<size_t>(now, 1)))) : 0;
        const double c0 = traceRounds ? threadCpuNow() : 0.0;
        if (!engines[r]->run(live[r], floor, limit, progress, done, expected, slot == 0)) cancelled = true;
        if (traceRounds) regionCpu[r] = threadCpuNow() - c0;
      });
      if (traceRounds) {
        // Each region's CPU seconds in this round, in task order: how
        // evenly they load the threads (a round's wall on an idle machine
        // is its longest thread) does not depend on the load then.
        std::fprintf(stderr, "    round %u regions' cpu:", levelRounds - 1);
        for (double c : regionCpu) std::fprintf(stderr, " %.5f", c);
        std::fprintf(stderr, "\n");
        const EngineStats a = sumStats(engines);
        std::fprintf(stderr,
                     "    round %u done: evaluated %zu collapses %zu tops %zu deleted %zu sank %zu notOurs %zu rejected "
                     "%zu wall %.4f cpu %.4f\n",
                     levelRounds - 1, a.evaluations - before.evaluations, a.collapses - before.collapses,
                     a.tops - before.tops, a.deletedTops - before.deletedTops, a.sank - before.sank,
                     a.notOurs - before.notOurs,
                     (a.rejectedTopology + a.rejectedFlip + a.rejectedSliver) -
                         (before.rejectedTopology + before.rejectedFlip + before.rejectedSliver),
                     secondsSince(roundWall), processCpuNow() - roundCpu);
      }
    }
    res.liveFaces = total();
    prevLive = live;
    if (traceOn) {
      const EngineStats x = sumStats(engines);
      std::fprintf(stderr,
                   "  level %u: %zu regions, %u rounds, evaluated %zu collapses %zu tops %zu deleted %zu sank %zu "
                   "notOurs %zu pushed %zu compactions %zu topo %zu flip %zu sliver %zu live %zu still shared %zu\n",
                   level, regions, levelRounds, x.evaluations, x.collapses, x.tops, x.deletedTops, x.sank, x.notOurs,
                   x.pushed, x.compactions, x.rejectedTopology, x.rejectedFlip, x.rejectedSliver, res.liveFaces,
                   shared.size());
    }
    mark("level: rounds");
    res.levels += levelRounds > 0;
    if (cancelled) break;
    if (level + 1 == lv.top) res.secondsParallel = secondsSince(t0);
  }
  if (lv.top == 0) res.secondsParallel = 0;
  res.secondsFinal = secondsSince(t0) - res.secondsParallel;
  res.cancelled = cancelled || isCancelled(progress);
  return res;
}

}  // namespace hs::mesh
