#pragma once
// A tileable blue-noise threshold map by Ulichney's void-and-cluster method
// (1993): every rank 0..side²-1 once, placed so that the pixels below any
// threshold are spread evenly with no low-frequency clumps (the dithering
// post effect's threshold, render/passes/stylised_passes.h). Computed, not
// shipped: 64 x 64 takes a few milliseconds, and the same side and seed
// give the same map on every machine (integer ties broken by index).
#include <cstdint>
#include <vector>

namespace hs {

// side x side ranks, row by row; side >= 2.
std::vector<uint32_t> blueNoiseRanks(int side, uint32_t seed = 1);

}  // namespace hs
