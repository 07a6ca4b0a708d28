#pragma once
// Per-vertex tangents for tangent-space normal maps, following MikkTSpace's
// definition (Mikkelsen 2008, what Blender, Substance and glTF bake with):
// the tangent is dP/du projected onto the vertex's tangent plane, summed
// over its triangles weighted by the corner angle; the fourth component is
// the handedness, sign(dot(cross(N, T), dP/dv)).
// So the bitangent, the direction of increasing v, is w * cross(N, T).
//
// Robust where MikkTSpace is: degenerate triangles (zero area or zero UV
// area) add nothing; a vertex whose triangles give no usable direction, and
// every vertex of a mesh without UVs, gets a tangent perpendicular to its
// normal chosen from the axes (finite, unit length, the same every time).
// At a mirror seam, where triangles of both handednesses share a vertex,
// MikkTSpace splits the vertex; this keeps one vertex and takes the side
// with the larger angle sum (the other side's corners there use its tangent).
#include <vector>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// One tangent per vertex (xyz unit, perpendicular to the normal; w = +-1).
std::vector<glm::vec4> computeTangents(const MeshData& mesh);

}  // namespace hs::mesh
