#pragma once
// Filling nodata holes (voids) in an elevation grid.
//
// Diffusion (default): the harmonic (Laplace) interpolation of the valid
// samples around each void: the smoothest surface that meets the void's rim,
// with no bumps and no flat plateaus. Solved coarse to fine: the valid
// samples are averaged down a pyramid, the coarsest level is filled by its
// mean, and each finer level starts from the upsampled coarser one and
// relaxes (red-black Gauss-Seidel, void samples only). A void of any size
// costs O(samples), and the result does not depend on the thread count.
// InverseDistance: GDAL's GDALFillNodata (inverse-distance weighting of the
// rim within a search distance, then smoothing); what it leaves unfilled
// (voids wider than the distance) is filled by diffusion.
#include <cstddef>
#include <string>
#include <vector>

#include "core/progress.h"

namespace hs::terrain {

enum class NodataFill { Diffusion, InverseDistance };
const char* nodataFillName(NodataFill f);

struct FillReport {
  size_t filled = 0;       // samples that were nodata
  size_t voids = 0;        // connected nodata regions (4-connected)
  size_t largestVoid = 0;  // samples in the largest
  size_t byDiffusion = 0;  // samples filled by diffusion (all of them for Diffusion)
  std::string method;
};

// values: w*h heights; valid: w*h flags (1 = data). Fills in place. Returns
// false only if there is no valid sample at all (nothing to fill from).
bool fillNodata(std::vector<float>& values, const std::vector<uint8_t>& valid, int w, int h, NodataFill method,
                double idwMaxDistancePixels, FillReport& report, const Progress* progress = nullptr);

}  // namespace hs::terrain
