#pragma once
// Levels of detail: a chain of ever coarser meshes, each with its error
// measured against the full-resolution mesh, and the GL-free rule a
// renderer uses to pick one: the coarsest level whose error, projected to
// the screen, stays under a pixel threshold.
#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/max_error_refine.h"

namespace hs::mesh {

struct LodOptions {
  int levels = 3;               // coarser levels after the base
  double ratio = 0.25;          // each level keeps this share of the previous one's triangles
  size_t minTriangles = 64;     // stop the chain before a level would go below this
  DecimateOptions decimate;     // flags for every level (target fields are set per level)
  ErrorOptions error;           // how each level's error is measured
  bool refine = true;           // refine each level against level 0 (max_error_refine.h)
  RefineOptions refinement;
};

struct Lod {
  MeshData mesh;                // level 0 is the base itself; others share its textures
  size_t triangles = 0;
  double hausdorff = 0;         // metres, symmetric, against level 0
  double hausdorffRel = 0;      // of level 0's bounding-box diagonal
  double meanError = 0;         // metres
  double samplesPerFace = 0;    // the rate its error was measured at (0: level 0, not measured)
  double decimateSeconds = 0, refineSeconds = 0, errorSeconds = 0;
};

struct LodChain {
  std::vector<Lod> levels;      // finest first; errors never decrease along it
  bool cancelled = false;
  std::string error;
};

// Builds the chain from `base` (level 0, error 0). Each level is decimated
// from the previous one (cheaper, and nested), measured against the base.
// Levels after the first drop their copy of the textures: they keep the
// material indices and draw with level 0's images.
LodChain buildLodChain(const MeshData& base, const LodOptions& options, const Progress* progress = nullptr);

// Screen-space error in pixels of a geometric error `errorMetres` seen at
// `distance` metres with a vertical field of view `fovY` (radians) on a
// viewport `viewportHeight` pixels tall (perspective projection).
double projectedErrorPixels(double errorMetres, double distance, double fovY, double viewportHeight);
// Its inverse: the distance from which `errorMetres` projects to at most
// `thresholdPixels` (infinity where no distance does: a threshold or field
// of view that is not positive).
double lodDistance(double errorMetres, double fovY, double viewportHeight, double thresholdPixels);

// Index of the coarsest level whose projected error is at most
// `thresholdPixels` (errors are per level, finest first, non-decreasing);
// 0 when even the finest is over it (or the distance is 0). `errors`
// may come straight from LodChain (hausdorff) or from a scene file.
int selectLod(const std::vector<double>& errors, double distance, double fovY, double viewportHeight,
              double thresholdPixels = 1.0);

}  // namespace hs::mesh
