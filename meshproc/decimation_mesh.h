#pragma once
// The OpenMesh half-edge mesh the decimator works on, and its fast builder.
//
// Points are double: the decimator works relative to the mesh's own centre,
// and quadric placement in double keeps the result independent of where the
// mesh sits in the world. Only status flags and the previous-halfedge link
// are requested; everything else the decimator needs (quadrics, wedges,
// regions) lives in plain arrays beside the mesh, indexed by handle, because
// OpenMesh properties cost an indirection per access and a vector<bool>
// property could not be written from two threads.
#include <cstdint>
#include <span>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/function_ref.h"

namespace hs::mesh {

struct DecimationTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using DecimationMesh = OpenMesh::TriMesh_ArrayKernelT<DecimationTraits>;

// Builds `mesh` from a manifold, consistently oriented triangle list (as
// splitNonManifold leaves it) with known corner twins, writing OpenMesh's
// arrays directly: add_face() checks and searches per face and is an order of
// magnitude slower on multi-million-triangle scans.
//
// Numbering: face f is triangle f; edge ids follow the first corner of each
// edge in triangle order; halfedge 2e runs along that corner, 2e+1 against
// it (inside the neighbouring face or on the boundary).
//
// pointOf(v): vertex v's position (called once a vertex, from the workers).
// firstCorner[v]: the first corner (in triangle order) that starts at v,
// which gives an interior vertex its outgoing halfedge; empty to have it
// searched here (a serial pass over every corner).
void buildDecimationMesh(std::span<const uint32_t> tris, std::span<const uint32_t> twin, size_t vertexCount,
                         FunctionRef<OpenMesh::Vec3d(size_t)> pointOf, DecimationMesh& mesh, unsigned threads,
                         std::span<const uint32_t> firstCorner = {});

}  // namespace hs::mesh
