#pragma once
// Height bounds per quadtree node, the input of CDLOD selection (each node's
// bounding box decides its LOD and its frustum test). Level 0 nodes cover
// leafCells x leafCells cells (the shared far edge included); each level up
// covers 2x2 nodes of the level below, up to one root. A brush stroke calls
// update() with its changed region: only the leaves under it and their
// ancestors are recomputed, O(region + log n).
#include <vector>

#include "terrain/heightfield.h"

namespace hs::terrain {

class MinMaxTree {
 public:
  MinMaxTree() = default;
  // leafCells: a power of two from 2 to 1024 (CDLOD leaf node size).
  MinMaxTree(const Heightfield& hf, int leafCells);

  int levels() const { return int(levels_.size()); }
  int leafCells() const { return leafCells_; }
  int nodesX(int level) const { return levels_[size_t(level)].nx; }
  int nodesY(int level) const { return levels_[size_t(level)].ny; }
  int nodeCells(int level) const { return leafCells_ << level; }
  HeightRange node(int level, int nx, int ny) const {
    const Level& l = levels_[size_t(level)];
    return l.nodes[size_t(ny) * size_t(l.nx) + size_t(nx)];
  }
  // Returns the number of nodes recomputed.
  size_t update(const Heightfield& hf, const Region& changed);

 private:
  struct Level {
    int nx = 0, ny = 0;
    std::vector<HeightRange> nodes;
  };
  HeightRange leafBounds(const Heightfield& hf, int nx, int ny) const;
  int leafCells_ = 32;
  std::vector<Level> levels_;
};

}  // namespace hs::terrain
