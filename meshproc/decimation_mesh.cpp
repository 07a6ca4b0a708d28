#include "meshproc/decimation_mesh.h"

#include <algorithm>

#include "core/large_pages.h"
#include "core/parallel.h"
#include "mesh/nonmanifold_split.h"
#include "core/uninit_array.h"

namespace hs::mesh {
namespace {

// OpenMesh's arrays are std::vectors, which resize() value-initialises on
// one thread: at 5M faces that is 390 MB of first touches, one page fault
// per 4 KiB, in one thread (1.4 s of the setup on this project's machines,
// where a fault costs about 15 us). Reserved first, their storage is asked
// for huge pages and faulted in on every worker before resize() writes it.
// Element 0 of each array is made to exist so that its address, the start
// of the reserved storage, can be taken; reserve() guarantees the capacity
// and resize() within it does not reallocate.
void reserveOnHugePages(DecimationMesh& mesh, size_t nv, size_t ne, size_t nf, unsigned threads) {
  mesh.reserve(nv, ne, nf);
  mesh.resize(1, 1, 1);
  auto prepare = [&](auto* first, size_t n) { adviseAndPopulate(first, n * sizeof(*first), threads); };
  prepare(&mesh.vertex(OpenMesh::VertexHandle(0)), nv);
  prepare(&mesh.edge(OpenMesh::EdgeHandle(0)), ne);
  prepare(&mesh.face(OpenMesh::FaceHandle(0)), nf);
  prepare(mesh.property(mesh.points_pph()).data_vector().data(), nv);
  prepare(mesh.property(mesh.vertex_status_pph()).data_vector().data(), nv);
  prepare(mesh.property(mesh.edge_status_pph()).data_vector().data(), ne);
  prepare(mesh.property(mesh.face_status_pph()).data_vector().data(), nf);
}

}  // namespace

void buildDecimationMesh(std::span<const uint32_t> tris, std::span<const uint32_t> twin, size_t vertexCount,
                         FunctionRef<OpenMesh::Vec3d(size_t)> pointOf, DecimationMesh& mesh, unsigned threads,
                         std::span<const uint32_t> firstCorner) {
  using OpenMesh::FaceHandle;
  using OpenMesh::HalfedgeHandle;
  using OpenMesh::VertexHandle;
  const size_t nv = vertexCount, nc = tris.size(), nf = nc / 3;
  auto owns = [&](size_t c) { return twin[c] == kNoCorner || c < twin[c]; };

  // Edge ids: a prefix count of owning corners, per range then combined, so
  // the numbering is the same for any number of workers.
  UninitArray<uint32_t> heOf(nc);  // every corner is numbered below
  const unsigned workers = std::max(1u, threads);
  const std::vector<size_t> rangeOwners = keptOffsets(nc, workers, owns);
  const size_t ne = rangeOwners[workers];
  parallelRanges(nc, workers, [&](size_t b, size_t e, unsigned w) {
    uint32_t next = uint32_t(rangeOwners[w]);
    for (size_t c = b; c < e; ++c)
      if (owns(c)) heOf[c] = 2 * next++;
  }, 1);
  parallelRanges(nc, workers, [&](size_t b, size_t e, unsigned) {
    for (size_t c = b; c < e; ++c)
      if (!owns(c)) heOf[c] = heOf[twin[c]] ^ 1u;
  }, 1);

  mesh.clean();
  reserveOnHugePages(mesh, nv, ne, nf, threads);
  mesh.resize(nv, ne, nf);

  // Inner halfedges: each face writes its own three, so workers never meet.
  parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t f = b; f < e; ++f) {
      const FaceHandle fh{int(f)};
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t c = uint32_t(f * 3 + k);
        const HalfedgeHandle h{int(heOf[c])};
        mesh.set_vertex_handle(h, VertexHandle(int(tris[nextCorner(c)])));
        mesh.set_face_handle(h, fh);
        mesh.set_next_halfedge_handle(h, HalfedgeHandle(int(heOf[nextCorner(c)])));
      }
      mesh.set_halfedge_handle(fh, HalfedgeHandle(int(heOf[f * 3])));
    }
  });

  // Boundary halfedges run against their inner corner; on a manifold mesh
  // each boundary vertex has exactly one leaving it, which links the loops.
  // (In parallel: each boundary vertex and each boundary halfedge is
  // written by one corner only.)
  UninitArray<int> boundaryOut(nv);
  parallelFill(boundaryOut.begin(), nv, -1, threads);
  parallelRanges(nc, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t c = b; c < e; ++c)
      if (twin[c] == kNoCorner) boundaryOut[tris[nextCorner(uint32_t(c))]] = int(heOf[c] ^ 1u);
  });
  parallelRanges(nc, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t c = b; c < e; ++c)
      if (twin[c] == kNoCorner) {
        const HalfedgeHandle bh{int(heOf[c] ^ 1u)};
        mesh.set_vertex_handle(bh, VertexHandle(int(tris[c])));
        mesh.set_next_halfedge_handle(bh, HalfedgeHandle(boundaryOut[tris[c]]));
      }
  });
  // Outgoing halfedge per vertex: the boundary one where there is one (an
  // OpenMesh invariant), else the first corner in triangle order, so ring
  // iteration starts at the same place on every run.
  if (firstCorner.size() == nv) {
    parallelRanges(nv, threads, [&](size_t b, size_t e, unsigned) {
      for (size_t v = b; v < e; ++v) {
        const VertexHandle vh{int(v)};
        const int out = boundaryOut[v] >= 0 ? boundaryOut[v] : firstCorner[v] < nc ? int(heOf[firstCorner[v]]) : -1;
        mesh.set_halfedge_handle(vh, HalfedgeHandle(out));
        mesh.point(vh) = pointOf(v);
      }
    });
    return;
  }
  std::vector<int> out(boundaryOut.begin(), boundaryOut.end());
  for (size_t c = 0; c < nc; ++c)
    if (out[tris[c]] < 0) out[tris[c]] = int(heOf[c]);
  parallelRanges(nv, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t v = b; v < e; ++v) {
      const VertexHandle vh{int(v)};
      mesh.set_halfedge_handle(vh, HalfedgeHandle(out[v]));
      mesh.point(vh) = pointOf(v);
    }
  });
}

}  // namespace hs::mesh
