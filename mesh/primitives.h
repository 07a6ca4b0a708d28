#pragma once
// Meshes made in code: the Materials panel's preview sphere, the material
// tests and benchmarks, the demo's detail samples.
#include "mesh/mesh_data.h"

namespace hs::mesh {

// A latitude-longitude sphere around the origin, Z up: `segments` around,
// `rings` from pole to pole, normals outward, UVs u = longitude (0..1 from
// +X towards +Y), v = 0 at the north pole. One submesh, one material.
MeshData uvSphere(float radius, int segments, int rings);

// A `size` x `size` square in the XY plane centred on the origin, facing +Z,
// cut into `cells` x `cells` quads; UVs repeat `uvRepeat` times across it
// (u along +X, v along -Y). One submesh, one material.
MeshData gridPlane(float size, int cells, float uvRepeat = 1.0f);

}  // namespace hs::mesh
