#pragma once
// The contents a tileset's full detail is made of: what a viewer draws
// with every tile refined as far as it goes. A hierarchy of the project's
// own is built from them when a tileset is too large to hold decoded
// (scene/tileset_import.h's streamed path), which also gives crack-free
// borders the tileset's own levels may lack.
//
// A tile's content is finest when nothing below it has content (a leaf of
// what is drawn), or when it refines by ADD (its children are drawn with
// it). A tile whose content did not come in with nothing below it to stand
// in would leave a hole: its nearest ancestor with content is then finest
// itself and everything under that ancestor is left out, the rule the
// in-core import follows (meshproc/cluster_from_tiles.h).
#include <string>
#include <vector>

#include "mesh/tileset_reader.h"

namespace hs::mesh {

struct FinestContents {
  std::vector<size_t> refs;            // indices into the listed contents, in their order
  size_t tilesKeptWhole = 0;           // ancestors standing in for a missing child
  size_t contentsLeftOut = 0;          // coarser contents, and those under a tile kept whole
  std::vector<std::string> warnings;   // one per tile kept whole, naming it and the child
};

FinestContents finestContents(const Tileset& tree, const std::vector<TilesetContentRef>& contents);

}  // namespace hs::mesh
