#pragma once
// Pieces every cluster hierarchy is made of, whether built here from a scan
// (cluster_hierarchy.cpp) or taken from a hierarchy made elsewhere
// (cluster_from_tiles.h): welding into the hierarchy's vertex pool,
// meshlets, bounding spheres.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "meshproc/cluster_hierarchy.h"

namespace hs::mesh {

// Appends `positions` (with `uvs`, when there is one per position) to
// `pool` / `poolUvs`, welding vertices of this input whose position and UV
// are the same (split normals do not cut the surface; a UV seam stays two
// vertices a side), and returns the triangles as pool indices, dropping
// those welded to a sliver. Indices past `positions` are the caller's to
// have dropped. `poolUvs` grows only when the input has UVs.
std::vector<uint32_t> weldForClusters(const std::vector<glm::vec3>& positions, const std::vector<glm::vec2>& uvs,
                                      const std::vector<uint32_t>& indices, std::vector<glm::vec3>& pool,
                                      std::vector<glm::vec2>& poolUvs);

// `tris` (pool indices, three a triangle) cut into meshlets of at most
// options.maxTriangles / maxVertices, each a list of pool-indexed
// triangles, by meshoptimizer (greedy by adjacency, in index order).
std::vector<std::vector<uint32_t>> meshletsOf(const std::vector<glm::vec3>& pool, const std::vector<uint32_t>& tris,
                                              const ClusterOptions& options);

// A sphere holding the vertices `indices[0 .. count)` name (centred on
// their box); none: an empty sphere.
LodSphere sphereOf(const std::vector<glm::vec3>& pool, const uint32_t* indices, size_t count);

// The smallest sphere holding both (a sphere holding the other is kept),
// grown by coordinateSlack so float rounding leaves neither outside.
LodSphere merged(const LodSphere& a, const LodSphere& b);

// What float rounding can move a sphere's centre by: eight units in the
// last place of its largest coordinate (the radius added).
float coordinateSlack(const LodSphere& s);

}  // namespace hs::mesh
