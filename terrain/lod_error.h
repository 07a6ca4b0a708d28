#pragma once
// Geometric error of each level of detail, the input of the CDLOD renderer's
// screen-space error bound.
//
// Level L draws every 2^L-th sample (a node of level L is a grid of
// leafCells quads, each 2^L samples wide) with the full-resolution mesh's
// triangle split (i,j)-(i+1,j+1). Its error is the largest vertical
// distance between that mesh and the full-resolution mesh, which (both being
// piecewise linear, the coarse triangles unions of fine ones) is attained at
// a full-resolution sample: e_L = max |h(x,y) - I_L(x,y)|. Samples beyond
// the last row/column read as the edge sample (the renderer's grid extends
// past the edge and discards those pixels), so I_L is defined everywhere.
//
// The maximum is kept per block (a 128^2 tile, or one coarse cell when that
// is larger): a block's error depends only on samples inside it and on its
// far edge, so an edit recomputes only the blocks under its region. error()
// is made monotone in L (max over the levels up to L), which the renderer's
// range construction relies on.
#include <vector>

#include "terrain/heightfield.h"

namespace hs::terrain {

class LodErrorMap {
 public:
  LodErrorMap() = default;
  // Levels 0..levels-1 (level 0 is the full resolution: error 0). Computes
  // everything (O(samples * levels), on the thread pool).
  LodErrorMap(const Heightfield& hf, int levels, int threads = 0);

  int levels() const { return int(levels_.size()); }
  // Largest vertical error of level L against the full-resolution mesh, metres.
  float error(int level) const;
  // Recomputes the blocks whose error depends on samples in `changed`.
  // Returns the number of samples evaluated (benchmarks).
  size_t update(const Heightfield& hf, const Region& changed, int threads = 0);
  // The same for several regions (a frame's worth of brush dabs): each
  // block is recomputed once however many regions touch it.
  size_t update(const Heightfield& hf, const std::vector<Region>& changed, int threads = 0);

 private:
  struct Level {
    int block = 128;       // samples per block side
    int nx = 0, ny = 0;    // blocks
    std::vector<float> blockError;
    float max = 0.0f;
  };
  void computeBlocks(const Heightfield& hf, int level, const std::vector<int>& blocks, int threads);
  void refreshMax();
  std::vector<Level> levels_;
  std::vector<float> monotone_;
  size_t evaluated_ = 0;
};

// Error of level L at one sample (reference implementation for tests):
// |h(x,y) - I_L(x,y)| with the clamped-edge convention above.
float lodErrorAt(const Heightfield& hf, int level, int x, int y);

}  // namespace hs::terrain
