#pragma once
// The parallel schedule of the decimator: regions (equal runs of the
// Morton order of the faces) decimate in rounds that share one error
// threshold, then merge pairwise, level by level, each level finishing in
// parallel the strips its pairs share, until one region is left, which
// finishes the count exactly (docs/meshes.md, "Two cores").
#include <cstddef>
#include <vector>

#include "core/progress.h"
#include "meshproc/collapse_engine.h"
#include "meshproc/decimate_trace.h"
#include "meshproc/decimation_state.h"

namespace hs::mesh {

struct ScheduleResult {
  bool cancelled = false;
  size_t liveFaces = 0;
  unsigned rounds = 0;   // parallel rounds, all levels together
  unsigned levels = 0;   // levels with more than one region that ran rounds
  std::vector<EngineStats> stats;  // every engine's, for the report
  size_t finalCollapses = 0;       // made by the last, single region
  double secondsParallel = 0;      // the levels of two or more regions
  double secondsFinal = 0;         // the last, single region
};

// Regions of the partition: vd[].region of every vertex is its region of
// `regions` (or kSharedRegion) as setUp left it, and nothing has collapsed.
// target 0: no triangle target (maxError alone limits the collapses).
ScheduleResult runRegionLevels(DecimationState& st, size_t regions, size_t target, unsigned threads,
                               const Progress* progress, DecimateTrace* trace);

}  // namespace hs::mesh
