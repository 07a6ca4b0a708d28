#include "meshproc/decimate.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <cmath>
#include <memory>
#include <numbers>
#include <unordered_map>

#include "core/large_pages.h"
#include "core/parallel.h"
#include "mesh/radix_sort.h"
#include "mesh/weld.h"
#include "meshproc/collapse_engine.h"
#include "meshproc/decimate_trace.h"
#include "meshproc/float_store.h"
#include "meshproc/decimation_state.h"
#include "meshproc/region_levels.h"
#include "core/uninit_array.h"

namespace hs::mesh {
namespace {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;
thread_local DecimateTrace* gTrace = nullptr;
inline void traceMark(const char* what) {
  if (gTrace) gTrace->mark(what);
}

// Per input face: which submesh (group) it belongs to. Faces no submesh
// covers get one extra group with the default material.
// Empty when one submesh covers every face (group 0 everywhere: the
// common case of a scan, and 5M entries written serially saved).
std::vector<uint16_t> faceGroups(const MeshData& in, std::vector<Submesh>& groups) {
  const size_t nf = in.triangleCount();
  groups = in.submeshes;
  if (groups.size() == 1 && groups[0].firstIndex == 0 && size_t(groups[0].indexCount) >= nf * 3) return {};
  std::vector<uint16_t> group(nf, UINT16_MAX);
  for (size_t g = 0; g < groups.size(); ++g) {
    const size_t b = groups[g].firstIndex / 3, e = std::min(nf, size_t(groups[g].firstIndex + groups[g].indexCount) / 3);
    for (size_t f = b; f < e; ++f)
      if (group[f] == UINT16_MAX) group[f] = uint16_t(std::min<size_t>(g, UINT16_MAX - 1));
  }
  if (std::find(group.begin(), group.end(), UINT16_MAX) != group.end()) {
    const uint16_t extra = uint16_t(std::min<size_t>(groups.size(), UINT16_MAX - 1));
    groups.push_back({0, 0, -1});
    for (auto& g : group)
      if (g == UINT16_MAX) g = extra;
  }
  return group;
}

struct Setup {
  UninitArray<uint32_t> omFaceOrig;  // OpenMesh face -> input face
  std::vector<uint32_t> wedgeRep;    // wedge -> an input vertex with its position and UV
  size_t degenerate = 0;
  size_t regions = 1;                // vd[].region is set for this partition (see regionCount)
};

// Regions: equal runs of the Morton-ordered faces. Their number depends on
// the mesh only, so the output does not depend on the thread count. At
// most 64: more regions lengthen the border strips, and their floors
// (region_levels.cpp) hold back more of the work for the serial last
// region at low targets (250 regions on the 5M scan tile: 2.2 s in it at
// 1%); 64 still balance well over the threads.
size_t regionCount(size_t nf, const DecimateOptions& opt) {
  const size_t per = std::max<size_t>(1000, opt.facesPerRegion);
  return std::clamp<size_t>((nf + per / 2) / per, 1, 64);
}
inline uint16_t regionOfFace(size_t f, size_t regions, size_t nf) { return uint16_t(f * regions / nf); }

// A vertex record's position (float) in double, loaded from the record
// after the store that rounded it (float_store.h says why).
inline glm::dvec3 recordPosition(const glm::vec3& stored) { return reloaded(stored); }

// Welds, orders spatially, splits non-manifold spots and builds the
// OpenMesh mesh plus every side array. Returns false with `error` set.
bool setUp(const MeshData& in, const DecimateOptions& opt, unsigned threads, DecimationState& st, Setup& su,
           DecimateReport& rep, std::string& error) {
  const size_t nfIn = in.triangleCount(), nvIn = in.vertexCount();
  const bool hasUv = in.uvs.size() == nvIn && nvIn > 0;

  // Topology is by exact position, so UV seams do not cut the surface;
  // wedges are by position + UV, so seams are known.
  PositionWedgeWeld weld =
      weldPositionsAndWedges(in.positions, hasUv ? std::span<const glm::vec2>(in.uvs) : std::span<const glm::vec2>(),
                             threads);
  const uint32_t nPos = weld.positionCount;
  const std::vector<uint32_t>& posOf = weld.posOf;
  const std::vector<uint32_t>& wedgeOf = weld.wedgeOf;
  const std::vector<uint32_t>& posRep = weld.posFirst;  // an input vertex at each position
  su.wedgeRep = std::move(weld.wedgeFirst);
  traceMark("weld");

  // Spatial (Morton) order of the faces: regions become contiguous ranges,
  // and neighbours sit close in memory, which matters more than anything
  // else for speed at millions of triangles.
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const auto& p : in.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  st.center = (glm::dvec3(lo) + glm::dvec3(hi)) * 0.5;
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-30f));
  const glm::vec3 scale = 1023.0f / extent;
  // Codes in parallel (degenerate faces marked), then compacted in order.
  constexpr uint64_t kDegenerate = ~uint64_t(0);
  UninitArray<uint64_t> order(nfIn);
  parallelRanges(nfIn, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t f = b; f < e; ++f) {
      const uint32_t* t = &in.indices[f * 3];
      const uint32_t pa = posOf[t[0]], pb = posOf[t[1]], pc = posOf[t[2]];
      if (pa == pb || pb == pc || pa == pc) {
        order[f] = kDegenerate;
        continue;
      }
      const glm::vec3 centroid = (in.positions[t[0]] + in.positions[t[1]] + in.positions[t[2]]) / 3.0f;
      const glm::uvec3 q = glm::uvec3(glm::clamp((centroid - lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f)));
      order[f] = (uint64_t(mortonCode10(q.x, q.y, q.z)) << 32) | f;
    }
  });
  size_t nf = 0;
  for (size_t f = 0; f < nfIn; ++f)
    if (order[f] != kDegenerate) order[nf++] = order[f];
  su.degenerate = nfIn - nf;
  radixSortByKey(std::span<uint64_t>(order.data(), nf), 30, threads);
  traceMark("morton sort");
  LargeVector<uint32_t> posOfOm, firstCorner;
  if (nf == 0) {
    error = "every face is degenerate (two corners at the same point); nothing to decimate";
    return false;
  }

  su.regions = regionCount(nf, opt);

  // Vertices numbered by first use in that order.
  // The corner where each vertex is numbered is its first corner, which
  // gives it its outgoing halfedge in buildDecimationMesh for free. In
  // parallel, the same numbers as one pass in corner order: each position
  // finds its first corner (an atomic minimum), the first corners are
  // counted per range and numbered in order, then every corner looks its
  // vertex up.
  const size_t nc = nf * 3;
  UninitArray<uint32_t> tris(nc), wedges(nc);  // every corner written below
  su.omFaceOrig.reset(nf);
  {
    UninitArray<std::atomic<uint32_t>> firstOfPos(nPos);
    parallelRanges(nPos, threads, [&](size_t b, size_t e, unsigned) {
      for (size_t p = b; p < e; ++p) firstOfPos[p].store(UINT32_MAX, std::memory_order_relaxed);
    });
    parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned) {
      for (size_t i = b; i < e; ++i) {
        const uint32_t f = uint32_t(order[i]);
        su.omFaceOrig[i] = f;
        for (size_t k = 0; k < 3; ++k) {
          const uint32_t iv = in.indices[size_t(f) * 3 + k], p = posOf[iv], c = uint32_t(i * 3 + k);
          tris[c] = p;  // a position for now
          wedges[c] = wedgeOf[iv];
          uint32_t cur = firstOfPos[p].load(std::memory_order_relaxed);
          while (c < cur && !firstOfPos[p].compare_exchange_weak(cur, c, std::memory_order_relaxed)) {
          }
        }
      }
    });
    order = UninitArray<uint64_t>();
    const unsigned workers = std::max(1u, threads);
    const std::vector<size_t> firsts =
        keptOffsets(nc, workers, [&](size_t c) { return firstOfPos[tris[c]].load(std::memory_order_relaxed) == c; });
    posOfOm.resize(firsts[workers]);
    firstCorner.resize(firsts[workers]);
    // Written for every position a valid face uses, the only ones read.
    UninitArray<uint32_t> omOfPos(nPos);
    parallelRanges(nc, workers, [&](size_t b, size_t e, unsigned w) {
      uint32_t next = uint32_t(firsts[w]);
      for (size_t c = b; c < e; ++c) {
        const uint32_t p = tris[c];
        if (firstOfPos[p].load(std::memory_order_relaxed) == c)
          omOfPos[p] = next, posOfOm[next] = p, firstCorner[next] = uint32_t(c), ++next;
      }
    }, 1);
    parallelRanges(nc, threads, [&](size_t b, size_t e, unsigned) {
      for (size_t c = b; c < e; ++c) tris[c] = omOfPos[tris[c]];
    });
  }
  uint32_t nv = uint32_t(posOfOm.size());
  traceMark("first-use numbering");

  // On a manifold mesh the split is the analysis alone (twins and counts).
  CornerTopology topo;
  std::vector<uint32_t> copiedFrom;
  rep.nonManifold = splitNonManifold(std::span<uint32_t>(tris.data(), tris.size()), nv, copiedFrom, topo, threads);
  traceMark("analyzeCorners");
  if (!topo.manifold()) {
    error = "the mesh has non-manifold edges that could not be split (" +
            std::to_string(topo.nonManifoldEdges) + " left)";
    return false;
  }
  if (!copiedFrom.empty()) {
    // The corners now on copies, in order (few: the defects' fans), found
    // in parallel.
    const std::vector<uint32_t> copyCorners = keptIndices(nc, threads, [&](size_t c) { return tris[c] >= nv; });
    // A split vertex's copies need wedges of their own: a wedge belongs to
    // one vertex, because a vertex that moves takes its wedges along.
    std::unordered_map<uint64_t, uint32_t> copyWedge;
    for (const uint32_t c : copyCorners) {
      const uint64_t key = (uint64_t(tris[c]) << 32) | wedges[c];
      auto [it, added] = copyWedge.try_emplace(key, uint32_t(su.wedgeRep.size()));
      if (added) su.wedgeRep.push_back(su.wedgeRep[wedges[c]]);
      wedges[c] = it->second;
    }
    for (uint32_t from : copiedFrom) posOfOm.push_back(posOfOm[from]);
    // A vertex that was split keeps the fan of its first corner (the split
    // gives the vertex's own id to the fan it meets first in corner order),
    // so only the copies need first corners.
    firstCorner.resize(posOfOm.size(), UINT32_MAX);
    for (const uint32_t c : copyCorners)
      if (firstCorner[tris[c]] == UINT32_MAX) firstCorner[tris[c]] = c;
    nv = uint32_t(posOfOm.size());
  }

  // Positions go straight into OpenMesh's point array (double, relative to
  // the centre), which the quadric pass below then reads.
  buildDecimationMesh(tris, topo.twin, nv, [&](size_t v) {
    const glm::dvec3 p = glm::dvec3(in.positions[posRep[posOfOm[v]]]) - st.center;
    return OpenMesh::Vec3d(p.x, p.y, p.z);
  }, st.mesh, threads, firstCorner);
  traceMark("buildDecimationMesh");
  st.bindArrays();

  std::vector<Submesh> groups;
  const std::vector<uint16_t> group = faceGroups(in, groups);
  st.hasSeams = hasUv || groups.size() > 1;
  st.fmaterial.reset(nf);
  parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned) {
    if (group.empty())
      std::fill(st.fmaterial.begin() + b, st.fmaterial.begin() + e, uint16_t(0));
    else
      for (size_t f = b; f < e; ++f) st.fmaterial[f] = group[su.omFaceOrig[f]];
  });
  st.fv = std::move(tris);
  st.fw = std::move(wedges);
  if (hasUv) {
    st.wedgeUv.reset(su.wedgeRep.size());
    parallelRanges(st.wedgeUv.size(), threads, [&](size_t b, size_t e, unsigned) {
      for (size_t w = b; w < e; ++w) st.wedgeUv[w] = in.uvs[su.wedgeRep[w]];
    });
  }

  traceMark("groups/wedgeUv");
  // Locks by input vertex, carried to every vertex at that position.
  std::vector<uint8_t> lockedPos;  // empty: nothing locked
  if (opt.lockedVertices.size() == nvIn) lockedPos.assign(nPos, 0);
  if (!lockedPos.empty())
    for (size_t v = 0; v < nvIn; ++v)
      if (opt.lockedVertices[v]) lockedPos[posOf[v]] = 1;

  // Classes, and quadrics: each vertex sums the planes of its own faces and
  // constrained edges, so vertices are independent and run in parallel.
  // Each face's plane is worked out by each of its three vertices, from
  // the face's corners in their own order (the same bits every time):
  // three times the arithmetic of one pass of planes, but no array of them
  // (200 MB at 5M faces, whose first touch cost more than the arithmetic).
  auto& m = st.mesh;
  const OpenMesh::Vec3d* const points = m.points();
  auto pointOf = [&](size_t v) { return glm::dvec3(points[v][0], points[v][1], points[v][2]); };
  struct Plane {
    glm::dvec3 n;
    double d, w;
  };
  auto planeOf = [&](size_t f) -> Plane {
    const glm::dvec3 pa = pointOf(st.fv[f * 3]), pb = pointOf(st.fv[f * 3 + 1]), pc = pointOf(st.fv[f * 3 + 2]);
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
    const double len = glm::length(n);
    // Weight sqrt(area), not area: the error then scales linearly with
    // size, so small features (a spike, a thin fin) are not outvoted by
    // the large faces around them (the weighting meshoptimizer uses;
    // measured lower Hausdorff on the bunny at every ratio than area).
    if (len > 0) return {n / len, -glm::dot(n / len, pa), std::sqrt(0.5 * len)};
    return {glm::dvec3(0.0), 0.0, 0.0};
  };
  // Vertices whose corners all use one wedge and one material cannot end a
  // seam edge: only edges at a "mixed" vertex need the full seam test.
  // (Every corner against its vertex's first corner, in parallel: the
  // stores all write 1, relaxed atomics keep that race defined.)
  UninitArray<std::atomic<uint8_t>> mixed(nv);
  parallelRanges(nv, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t v = b; v < e; ++v) mixed[v].store(0, std::memory_order_relaxed);
  });
  parallelRanges(st.fv.size(), threads, [&](size_t b, size_t e, unsigned) {
    for (size_t c = b; c < e; ++c) {
      const uint32_t v = st.fv[c], fc = firstCorner[v];
      if (st.fw[c] != st.fw[fc] || st.fmaterial[c / 3] != st.fmaterial[fc / 3]) mixed[v].store(1, std::memory_order_relaxed);
    }
  });
  firstCorner = LargeVector<uint32_t>();
  std::atomic<size_t> nBoundary{0}, nSeam{0}, nFixed{0}, nLocked{0};
  traceMark("mixed");
  // One pass writes each vertex's whole record: quadric, position, class,
  // and its region of the partition (decimate() cuts the Morton order into
  // su.regions equal runs; a vertex with faces in two is shared).
  const size_t regions = su.regions;
  st.vd.reset(nv);
  st.polyNbr.reset(nv * 2);
  parallelRanges(nv, threads, [&](size_t b, size_t e, unsigned) {
    size_t cb = 0, cs = 0, cf = 0, cl = 0;
    for (size_t vi = b; vi < e; ++vi) {
      const VertexHandle v{int(vi)};
      const HalfedgeHandle start = m.halfedge_handle(v);
      auto& d = st.vd[vi];
      d.p = glm::vec3(pointOf(vi));
      d.region = kSharedRegion;
      if (!start.is_valid()) {
        d.q = QuadricF::store(Quadric{});
        d.cls = VertexClass::Fixed;
        continue;
      }
      // The quadric is relative to the stored (float) position: planes'
      // offsets are taken from it, read back from the record (see
      // recordPosition).
      const glm::dvec3 pv = recordPosition(d.p);
      int boundaryEdges = 0, seamEdges = 0;
      uint32_t lineNbr[2] = {uint32_t(vi), uint32_t(vi)};  // the first two polyline neighbours seen
      uint16_t region = kSharedRegion;
      bool shared = false;
      Quadric q{};
      HalfedgeHandle it = start;
      do {
        const FaceHandle f = m.face_handle(it);
        if (f.is_valid()) {
          const Plane pl = planeOf(size_t(f.idx()));
          if (pl.w > 0) q += Quadric::plane(pl.n, pl.d + glm::dot(pl.n, pv), pl.w);
          const uint16_t fr = regionOfFace(size_t(f.idx()), regions, nf);
          if (region == kSharedRegion) region = fr;
          else if (fr != region) shared = true;
        }
        const HalfedgeHandle back = m.opposite_halfedge_handle(it);
        const EdgeKind kind = !f.is_valid() || !m.face_handle(back).is_valid() ? EdgeKind::Boundary
                              : mixed[vi].load(std::memory_order_relaxed) ||
                                        mixed[size_t(m.to_vertex_handle(it).idx())].load(std::memory_order_relaxed)
                                    ? st.edgeKind(it)
                                                                                         : EdgeKind::Interior;
        if (kind != EdgeKind::Interior) {
          const int seen = boundaryEdges + seamEdges;
          if (seen < 2) lineNbr[seen] = uint32_t(m.to_vertex_handle(it).idx());
          (kind == EdgeKind::Boundary ? boundaryEdges : seamEdges)++;
          // A plane through the edge, perpendicular to each face beside it:
          // moving the polyline sideways costs, so boundaries and seams are
          // simplified by how far they bend, not left to chance.
          const glm::dvec3 edge = pointOf(size_t(m.to_vertex_handle(it).idx())) - pv;
          const double len2 = glm::dot(edge, edge);
          for (const FaceHandle g : {f, m.face_handle(m.opposite_halfedge_handle(it))}) {
            if (!g.is_valid()) continue;
            glm::dvec3 side = glm::cross(edge, planeOf(size_t(g.idx())).n);
            const double sl = glm::length(side);
            if (!(sl > 0)) continue;
            side /= sl;
            const double cw = std::sqrt(len2);  // the edge length, to match the faces' sqrt(area)
            q += Quadric::plane(side, 0.0, kind == EdgeKind::Boundary ? cw : 0.5 * cw);  // through pv
          }
        }
        it = m.next_halfedge_handle(m.opposite_halfedge_handle(it));
      } while (it != start);
      d.q = QuadricF::store(q);
      d.region = shared ? kSharedRegion : region;

      VertexClass c = VertexClass::Free;
      if (boundaryEdges == 2 && seamEdges == 0)
        c = opt.lockBoundaries ? VertexClass::Fixed : VertexClass::BoundaryLine;
      else if (seamEdges == 2 && boundaryEdges == 0)
        c = VertexClass::SeamLine;
      else if (boundaryEdges || seamEdges)
        c = VertexClass::Fixed;
      if (!lockedPos.empty() && lockedPos[posOfOm[vi]]) c = VertexClass::Fixed, ++cl;
      d.cls = c;
      if (c == VertexClass::BoundaryLine || c == VertexClass::SeamLine)
        st.polyNbr[vi * 2] = lineNbr[0], st.polyNbr[vi * 2 + 1] = lineNbr[1];
      cb += boundaryEdges > 0;
      cs += seamEdges > 0;
      cf += c == VertexClass::Fixed;
    }
    nBoundary += cb, nSeam += cs, nFixed += cf, nLocked += cl;
  });
  rep.boundaryVertices = nBoundary, rep.seamVertices = nSeam, rep.fixedVertices = nFixed;
  rep.lockedVertices = nLocked;
  st.estate.reset(m.n_edges());
  parallelFill(st.estate.begin(), st.estate.size(), uint8_t(0), threads);
  rep.degenerateFacesRemoved = su.degenerate;
  traceMark("quadrics+classes");

  return true;
}

// Writes the surviving faces back in input order, grouped by the input's
// submeshes, with vertices (wedges) in input order: at 100% the output is
// the input.
MeshData extract(const MeshData& in, const DecimationState& st, const Setup& su, bool keepTextures, unsigned threads) {
  MeshData out;
  out.origin = in.origin;
  out.materials = in.materials;
  if (keepTextures) out.textures = in.textures;
  const size_t nfIn = in.triangleCount(), nf = st.fv.size() / 3;
  const size_t nWedge = su.wedgeRep.size();
  // Which decimator face each input face became (if it lives), and the
  // vertex of every wedge a live face uses. In parallel: each live face
  // writes its own input face's slot, and the wedge slots its corners
  // name; corners of two faces name one wedge with the same vertex (a
  // wedge belongs to one vertex), written as relaxed atomic stores.
  UninitArray<uint32_t> omOfInput(nfIn), wedgeVertex(nWedge);
  parallelFill(omOfInput.begin(), nfIn, UINT32_MAX, threads);
  parallelFill(wedgeVertex.begin(), nWedge, UINT32_MAX, threads);
  std::atomic<size_t> live{0};
  parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned) {
    size_t n = 0;
    for (size_t f = b; f < e; ++f)
      if (!st.faceStatus[f].deleted()) {
        omOfInput[su.omFaceOrig[f]] = uint32_t(f);
        for (size_t k = 0; k < 3; ++k)
          std::atomic_ref<uint32_t>(wedgeVertex[st.fw[f * 3 + k]]).store(st.fv[f * 3 + k], std::memory_order_relaxed);
        ++n;
      }
    live += n;
  });
  const size_t liveFaces = live;
  traceMark("output: faces");
  // Output vertices: the used wedges, numbered in wedge order.
  UninitArray<uint32_t> outOf(nWedge);
  const unsigned workers = std::max(1u, threads);
  const std::vector<size_t> firstOut = keptOffsets(nWedge, workers, [&](size_t x) { return wedgeVertex[x] != UINT32_MAX; });
  parallelRanges(nWedge, workers, [&](size_t b, size_t e, unsigned w) {
    uint32_t next = uint32_t(firstOut[w]);
    for (size_t x = b; x < e; ++x) outOf[x] = wedgeVertex[x] != UINT32_MAX ? next++ : UINT32_MAX;
  }, 1);
  const uint32_t nOut = uint32_t(firstOut[workers]);
  const bool hasUv = !st.wedgeUv.empty();
  resizeOnHugePages(out.positions, nOut, threads);
  if (hasUv) resizeOnHugePages(out.uvs, nOut, threads);
  parallelRanges(nWedge, threads, [&](size_t b, size_t e, unsigned) {
    for (size_t w = b; w < e; ++w) {
      if (outOf[w] == UINT32_MAX) continue;
      // OpenMesh's points hold the positions in double (see Vertex).
      const OpenMesh::Vec3d& p = st.mesh.point(VertexHandle(int(wedgeVertex[w])));
      out.positions[outOf[w]] = glm::vec3(glm::dvec3(p[0], p[1], p[2]) + st.center);
      if (hasUv) out.uvs[outOf[w]] = st.wedgeUv[w];
    }
  });
  traceMark("output: vertices");

  std::vector<Submesh> groups;
  const std::vector<uint16_t> group = faceGroups(in, groups);
  if (groups.size() == 1) {
    // One group: straight into the index list, in parallel (each range
    // starts where the live faces of the ranges before it end).
    resizeOnHugePages(out.indices, liveFaces * 3, threads);
    const std::vector<size_t> start = keptOffsets(nfIn, workers, [&](size_t f) { return omOfInput[f] != UINT32_MAX; });
    parallelRanges(nfIn, workers, [&](size_t b, size_t e, unsigned w) {
      size_t n = start[w] * 3;
      for (size_t f = b; f < e; ++f) {
        const uint32_t o = omOfInput[f];
        if (o == UINT32_MAX) continue;
        for (size_t k = 0; k < 3; ++k) out.indices[n++] = outOf[st.fw[size_t(o) * 3 + k]];
      }
    }, 1);
    if (!out.indices.empty()) out.submeshes.push_back({0, uint32_t(out.indices.size()), groups[0].material});
  } else {
    std::vector<std::vector<uint32_t>> perGroup(groups.size());
    for (size_t f = 0; f < nfIn; ++f) {
      const uint32_t o = omOfInput[f];
      if (o == UINT32_MAX) continue;
      auto& dst = perGroup[group[f]];
      for (size_t k = 0; k < 3; ++k) dst.push_back(outOf[st.fw[size_t(o) * 3 + k]]);
    }
    out.indices.reserve(liveFaces * 3);
    for (size_t g = 0; g < groups.size(); ++g) {
      if (perGroup[g].empty()) continue;
      out.submeshes.push_back({uint32_t(out.indices.size()), uint32_t(perGroup[g].size()), groups[g].material});
      out.indices.insert(out.indices.end(), perGroup[g].begin(), perGroup[g].end());
    }
  }
  traceMark("output: indices");
  computeVertexNormals(out, threads);
  return out;
}

}  // namespace

DecimateResult decimate(const MeshData& in, const DecimateOptions& opt, const Progress* progress) {
  const auto t0 = DecimateClock::now();
  DecimateResult result;
  DecimateReport& rep = result.report;
  const size_t nfIn = in.triangleCount(), nvIn = in.vertexCount();
  rep.trianglesIn = nfIn;
  rep.verticesIn = nvIn;
  const unsigned threads = resolveThreads(opt.threads);
  rep.threads = threads;

  if (in.indices.size() % 3 != 0) {
    result.error = "the index list is not a whole number of triangles";
    return result;
  }
  for (uint32_t idx : in.indices)
    if (idx >= nvIn) {
      result.error = "a face refers to vertex " + std::to_string(idx) + " of " + std::to_string(nvIn) +
                     "; clean the mesh first (cleanMesh quarantines such faces)";
      return result;
    }
  for (const auto& p : in.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      result.error = "the mesh has NaN or infinite coordinates; clean the mesh first (cleanMesh quarantines them)";
      return result;
    }
  if (nfIn == 0) {
    result.error = "the mesh has no faces";
    return result;
  }

  const double ratio = std::clamp(std::isfinite(opt.targetRatio) ? opt.targetRatio : 1.0, 0.0, 1.0);
  size_t target = opt.targetTriangles > 0 ? std::min(opt.targetTriangles, nfIn) : size_t(std::llround(ratio * double(nfIn)));
  rep.targetTriangles = target;
  if (target >= nfIn) {
    // Nothing to remove: the input is the answer, unchanged.
    result.mesh = in;
    rep.trianglesOut = nfIn, rep.verticesOut = nvIn, rep.targetReached = true;
    rep.secondsTotal = secondsSince(t0);
    return result;
  }

  reportProgress(progress, 0.0, "Preparing decimation");
  DecimateTrace trace;
  gTrace = &trace;
  struct ClearTrace {
    ~ClearTrace() { gTrace = nullptr; }
  } clearTrace;
  traceMark("validate");
  DecimationState st;
  st.cosMaxNormalDeviation = std::cos(std::clamp(opt.maxNormalDeviationDeg, 0.0, 180.0) * std::numbers::pi / 180.0);
  st.minQuality = std::clamp(opt.minTriangleQuality, 0.0, 1.0);
  st.maxErrorSq = std::isfinite(opt.maxError) ? opt.maxError * opt.maxError : HUGE_VAL;
  Setup su;
  if (!setUp(in, opt, threads, st, su, rep, result.error)) return result;
  rep.secondsSetup = secondsSince(t0);
  if (isCancelled(progress)) {
    result.cancelled = true;
    return result;
  }

  // The parallel schedule (region_levels.h): regions in rounds, merged
  // level by level, the last region finishing the count exactly.
  rep.regions = unsigned(su.regions);
  const bool countTarget = target > 0;
  ScheduleResult sched = runRegionLevels(st, su.regions, target, threads, progress, &trace);
  rep.rounds = sched.rounds;
  rep.levels = sched.levels;
  rep.lastRegionCollapses = sched.finalCollapses;
  rep.secondsRegions = sched.secondsParallel;
  rep.secondsLastRegion = sched.secondsFinal;
  if (sched.cancelled) {
    result.cancelled = true;
    return result;
  }
  const std::vector<EngineStats>& stats = sched.stats;

  for (const auto& s : stats) {
    rep.collapses += s.collapses;
    rep.rejectedTopology += s.rejectedTopology;
    rep.rejectedFlip += s.rejectedFlip;
    rep.rejectedSliver += s.rejectedSliver;
    rep.maxEstimatedError = std::max(rep.maxEstimatedError, std::sqrt(s.maxErrorSq));
  }

  reportProgress(progress, 0.92, "Writing decimated mesh");
  const auto t3 = DecimateClock::now();
  result.mesh = extract(in, st, su, opt.copyTextures, threads);
  rep.trianglesOut = result.mesh.triangleCount();
  rep.verticesOut = result.mesh.vertexCount();
  rep.targetReached = !countTarget || rep.trianglesOut <= target;
  rep.secondsOutput = secondsSince(t3);
  traceMark("output");
  rep.secondsTotal = secondsSince(t0);
  reportProgress(progress, 1.0, "Decimated");
  return result;
}

const std::vector<ParamDecl>& decimateTargetDecls() {
  static const std::vector<ParamDecl> decls = {
      {.key = "target_ratio_pct", .label = "Share of the triangles", .unit = Unit::Percent, .min = 0.01, .max = 100.0,
       .help = "decimate to this share of the triangles", .editor = true, .decimals = 2},
      {.key = "target_triangles", .label = "Triangle count", .min = 4, .max = 2147483647, .integer = true,
       .help = "decimate to this many triangles", .editor = true},
  };
  return decls;
}

bool parseDecimateTarget(std::string_view text, DecimateOptions& options, std::string& error) {
  const std::string quoted = "'" + std::string(text) + "'";
  const std::string usage = " (use e.g. 500k, 2M, 120000 or 10%)";
  // The number and its suffix: '%' a share, k/M thousands/millions of triangles.
  std::string_view t = text;
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
  if (t.empty()) {
    error = "empty decimation target" + usage;
    return false;
  }
  double scale = 1.0;
  bool percent = false;
  const char last = t.back();
  if (last == '%') percent = true, t.remove_suffix(1);
  else if (last == 'k' || last == 'K') scale = 1e3, t.remove_suffix(1);
  else if (last == 'm' || last == 'M') scale = 1e6, t.remove_suffix(1);
  // The number itself is read like any declared number (core/params.h).
  const ParamDecl number{.key = "decimation target", .label = "decimation target", .min = 0.0,
                         .max = std::numeric_limits<double>::max()};
  std::string why;
  const std::optional<Json> v = parseParam(number, t, why);
  if (!v || !(v->get<double>() > 0.0)) {
    error = "cannot read decimation target " + quoted + usage;
    return false;
  }
  const ParamDecl& target = paramIn(decimateTargetDecls(), percent ? "target_ratio_pct" : "target_triangles");
  const double value = percent ? v->get<double>() : std::round(v->get<double>() * scale);
  if (value < target.min || value > target.max) {
    const bool above = value > target.max;
    error = "decimation target " + quoted + " is " + (above ? "above " : "below ") +
            formatNumber(above ? target.max : target.min) + (percent ? "%" : " triangles") + " (" + rangeText(target) +
            ")";
    return false;
  }
  if (percent) {
    options.targetRatio = value / 100.0;
    options.targetTriangles = 0;
  } else {
    options.targetTriangles = size_t(value);
  }
  return true;
}

}  // namespace hs::mesh
