#pragma once
// A cluster hierarchy from levels of detail made elsewhere (issue 38 item
// 5: 3D Tiles; mesh/tileset_reader.h reads them, scene/tileset_import.h
// places them): each tile's triangles cut into clusters, and the tile tree
// turned into the hierarchy's groups, so the same cut, pages, streaming
// and budgets serve it as a hierarchy built here (cluster_hierarchy.h).
//
// A tile with children is a group: the clusters of its own content are
// what the group made (its LOD test: the tile's geometric error over a
// sphere holding it and everything below), its children's clusters are
// what was simplified in it (a cut swaps the ones for the others, as 3D
// Tiles' REPLACE refinement does). A leaf's clusters are level 0 (error 0:
// the finest there is). An ADD tile's content stays drawn with its
// children: it is kept twice, as what its group made and as a level-0
// child of that group. A tile without content is passed through: its
// children hang under its nearest ancestor with content (or are roots).
//
// A tile whose content did not come in and that has no content below it
// would leave a hole where its parent is refined: its nearest ancestor with
// content is then not refined at all (its children are left out, reported).
//
// Errors must only grow up the tree: a tile whose geometric error is below
// a descendant's is raised to it (reported). Unlike a hierarchy built
// here, the borders between tiles were not locked together: where tiles
// of different levels meet, a cut can show the cracks the tileset itself
// has in Cesium and other 3D Tiles viewers.
#include <string>
#include <vector>

#include "meshproc/cluster_hierarchy.h"

namespace hs::mesh {

struct LodTile {
  int parent = -1;       // index into the list (parents first); -1: a root
  float error = 0.0f;    // metres: the error of drawing this tile and not its children
  bool additive = false; // its children are drawn with it (3D Tiles ADD)
  bool missing = false;  // it names content that did not come in
  std::string name;      // for messages: the content file(s)
  std::vector<glm::vec3> positions;  // the hierarchy's local frame
  std::vector<glm::vec2> uvs;        // one per position, or none
  std::vector<uint32_t> indices;     // triangles
};

struct TileHierarchyReport {
  size_t tilesWithContent = 0, tilesPassedThrough = 0;
  size_t tilesLeftOut = 0;  // below an ancestor kept whole for a missing content
  size_t errorsRaised = 0;  // tiles whose error was below a descendant's
  size_t additiveCopies = 0, additiveCopyTriangles = 0;
  std::vector<std::string> warnings;
};

// The hierarchy of `tiles` (local coordinates about `origin`). UVs are kept
// when every tile with content has them.
ClusterHierarchy clusterHierarchyOfTiles(const std::vector<LodTile>& tiles, const glm::dvec3& origin,
                                         const ClusterOptions& options = {}, TileHierarchyReport* report = nullptr);

}  // namespace hs::mesh
