#pragma once
// Everything the decimator keeps beside the OpenMesh mesh, in flat arrays
// indexed by OpenMesh handle index. Shared by the setup (decimate.cpp) and
// the collapse loops (collapse_engine.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "meshproc/decimation_mesh.h"
#include "meshproc/quadric.h"
#include "core/uninit_array.h"

namespace hs::mesh {

// What a vertex may do in a collapse.
enum class VertexClass : uint8_t {
  Free,          // interior, single wedge: may go anywhere the error allows
  BoundaryLine,  // on one open boundary, two boundary edges: slides along it onto a neighbour
  SeamLine,      // on one UV seam or material border, two seam edges: same, along the seam
  Fixed,         // locked, or where polylines meet, end or branch: never moves or goes
};

// What an edge is.
enum class EdgeKind : uint8_t { Interior, Boundary, Seam };

constexpr uint16_t kSharedRegion = UINT16_MAX;  // vertex with faces in more than one region

struct DecimationState {
  DecimationMesh mesh;
  glm::dvec3 center{0.0};  // mesh.point() is relative to this (input-local coordinates)

  // Per vertex, everything a cost evaluation reads, in one 64-byte record
  // (one cache line) instead of three arrays: evaluations are most of the
  // decimator's time, and at millions of vertices they wait on memory.
  // The position is in float relative to `center`: as fine as the input's
  // own float positions at the mesh's far side, coarser than them only
  // near a local origin far from the centre (61 um at 500 m; the
  // decimation test with millimetre triangles there). The quadric is in float relative to that position
  // (QuadricF: relative to the vertex nothing large cancels), so its
  // origin moves with the vertex and every collapse re-expresses it.
  // OpenMesh's point property keeps the positions in double for the
  // output: the input's, and for a vertex a collapse moves the place its
  // solve chose (written by the collapse, never read by the loops), so the
  // float rounding here never reaches the result. Double records
  // (quadric, position) were 128 bytes, two cache lines an evaluation and
  // a fan check paid per vertex.
  // Allocated without zeroing (hundreds of MB at scale) and filled by the
  // setup's parallel passes.
  struct alignas(64) Vertex {
    QuadricF q;  // relative to p
    glm::vec3 p;
    VertexClass cls;
    uint16_t region;  // its region, or kSharedRegion
  };
  static_assert(sizeof(Vertex) == 64);
  UninitArray<Vertex> vd;
  UninitArray<uint32_t> fv;           // per face: 3 vertex ids, in winding order
  UninitArray<uint32_t> fw;           // per face: the wedge (vertex+UV) of each corner
  UninitArray<uint16_t> fmaterial;    // per face: input submesh index
  UninitArray<uint8_t> estate;        // per edge: kQueued | kDirty | kGone (collapse_engine.h)
  UninitArray<glm::vec2> wedgeUv;     // per wedge (empty without UVs)
  // Per vertex, two entries: a BoundaryLine or SeamLine vertex's two
  // neighbours along its polyline in the input (other vertices' entries
  // are not written). Polyline vertices never move and only merge along
  // their polyline, so the polyline left at any time is a subsequence of
  // the input's, and the input vertices between two neighbours on it are
  // exactly those their segment now stands for (polylineErrorSq).
  UninitArray<uint32_t> polyNbr;

  // Raw views into OpenMesh's status arrays (set once the mesh is built;
  // collapses never reallocate them). A property lookup by handle walks
  // the property container on every access, which showed in profiles.
  OpenMesh::Attributes::StatusInfo* vertexStatus = nullptr;
  OpenMesh::Attributes::StatusInfo* edgeStatus = nullptr;
  OpenMesh::Attributes::StatusInfo* faceStatus = nullptr;
  bool hasSeams = true;  // false: no UVs and one material, so no edge is a seam

  void bindArrays() {
    vertexStatus = mesh.property(mesh.vertex_status_pph()).data_vector().data();
    edgeStatus = mesh.property(mesh.edge_status_pph()).data_vector().data();
    faceStatus = mesh.property(mesh.face_status_pph()).data_vector().data();
  }
  glm::dvec3 point(int v) const { return glm::dvec3(vd[size_t(v)].p); }
  // The sum of two vertices' quadrics in the frame whose origin is `origin`
  // (relative to the centre, like the positions).
  Quadric quadricAt(size_t a, size_t b, const glm::dvec3& origin) const {
    return vd[a].q.load().translated(origin - point(int(a))) + vd[b].q.load().translated(origin - point(int(b)));
  }

  double cosMaxNormalDeviation = 0.5;
  double minQuality = 0.1;
  double maxErrorSq = 1e300;
  // Share of the squared edge length in the heap key (see engine): a
  // tie-break for zero-error collapses of flat ground. 1e-5, i.e. (0.3% of
  // the edge)^2: at 1e-4 it was (1% of the edge)^2, as large as the errors
  // themselves on a scan with millimetre detail on 17 cm faces, and chose
  // short edges over cheap ones (docs/meshes.md, "Quad-dominant meshes").
  double lengthWeight = 1e-5;

  // Removing polyline vertex `gone` by merging it into its neighbour
  // `stays` along the polyline: the largest squared distance from the new
  // segment (stays to gone's other neighbour) of the input vertices it
  // then stands for (those between stays and gone, gone, those between
  // gone and its other neighbour), found by walking the input polyline.
  // A face quadric measures how far the neighbour lies from the removed
  // vertex's planes, averaged over both ends' planes, and misses a line
  // that sags between its kept vertices (docs/meshes.md, "Quad-dominant
  // meshes"). HUGE_VAL where the polyline is too short to lose a vertex.
  // Safe while regions run in parallel: the walk reads input positions
  // and neighbours (never written), the deleted flags of vertices already
  // gone (final) and those of the two live ends, which are neighbours of
  // `gone` and so belong to the calling engine's region or are shared;
  // the vertices between were merged by collapses at `gone` or at those
  // ends, i.e. by this engine or by an earlier phase.
  double polylineErrorSq(uint32_t gone, uint32_t stays) const {
    constexpr int kMaxWalk = 1 << 16;  // a guard: the walk ends at a live vertex long before
    uint32_t ends[2];
    for (int side = 0; side < 2; ++side) {
      uint32_t prev = gone, x = polyNbr[size_t(gone) * 2 + size_t(side)];
      int steps = 0;
      while (vertexStatus[x].deleted() && x != gone && ++steps < kMaxWalk) {
        const uint32_t next = polyNbr[size_t(x) * 2] == prev ? polyNbr[size_t(x) * 2 + 1] : polyNbr[size_t(x) * 2];
        prev = x, x = next;
      }
      if (x == gone || steps >= kMaxWalk) return HUGE_VAL;
      ends[side] = x;
    }
    if (ends[0] == ends[1] || (ends[0] != stays && ends[1] != stays)) return HUGE_VAL;
    const uint32_t other = ends[0] == stays ? ends[1] : ends[0];
    const glm::dvec3 a = point(int(stays)), ab = point(int(other)) - a;
    const double len2 = glm::dot(ab, ab);
    auto distSq = [&](uint32_t x) {
      const glm::dvec3 ax = point(int(x)) - a;
      const double t = len2 > 0 ? glm::clamp(glm::dot(ax, ab) / len2, 0.0, 1.0) : 0.0;
      const glm::dvec3 d = ax - t * ab;
      return glm::dot(d, d);
    };
    double worst = distSq(gone);
    for (int side = 0; side < 2; ++side) {
      uint32_t prev = gone, x = polyNbr[size_t(gone) * 2 + size_t(side)];
      while (x != ends[side]) {
        worst = std::max(worst, distSq(x));
        const uint32_t next = polyNbr[size_t(x) * 2] == prev ? polyNbr[size_t(x) * 2 + 1] : polyNbr[size_t(x) * 2];
        prev = x, x = next;
      }
    }
    return worst;
  }

  uint32_t wedgeAt(uint32_t f, uint32_t v) const {
    const uint32_t* p = &fv[size_t(f) * 3];
    return fw[size_t(f) * 3 + (p[0] == v ? 0 : p[1] == v ? 1 : 2)];
  }

  // Boundary: one face. Seam: the faces differ in material, or in the wedge
  // (vertex + UV) they use at either end, i.e. the texture is cut there.
  EdgeKind edgeKind(OpenMesh::HalfedgeHandle h) const {
    const OpenMesh::HalfedgeHandle o = mesh.opposite_halfedge_handle(h);
    const OpenMesh::FaceHandle f = mesh.face_handle(h), g = mesh.face_handle(o);
    if (!f.is_valid() || !g.is_valid()) return EdgeKind::Boundary;
    if (!hasSeams) return EdgeKind::Interior;
    const uint32_t fi = uint32_t(f.idx()), gi = uint32_t(g.idx());
    if (fmaterial[fi] != fmaterial[gi]) return EdgeKind::Seam;
    const uint32_t a = uint32_t(mesh.to_vertex_handle(o).idx()), b = uint32_t(mesh.to_vertex_handle(h).idx());
    if (wedgeAt(fi, a) != wedgeAt(gi, a) || wedgeAt(fi, b) != wedgeAt(gi, b)) return EdgeKind::Seam;
    return EdgeKind::Interior;
  }
};

}  // namespace hs::mesh
