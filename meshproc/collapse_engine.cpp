#include "meshproc/collapse_engine.h"

#include <algorithm>
#include <cmath>

namespace hs::mesh {
namespace {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;


// Heap order: smaller key first; equal keys by edge id (a deterministic tie-break).
inline bool before(const CollapseEngine::Entry& a, const CollapseEngine::Entry& b) { return a.packed < b.packed; }

bool removable(VertexClass c, EdgeKind k) {
  switch (c) {
    case VertexClass::Free: return true;  // a free vertex has interior edges only
    case VertexClass::BoundaryLine: return k == EdgeKind::Boundary;
    case VertexClass::SeamLine: return k == EdgeKind::Seam;
    case VertexClass::Fixed: return false;
  }
  return false;
}


}  // namespace

CollapseEngine::CollapseEngine(DecimationState& state, uint16_t region, unsigned level)
    : s_(state), m_(state.mesh), region_(region), level_(level) {
  ring_.reserve(64);
}


bool CollapseEngine::evaluate(uint32_t edge, Plan& plan) const {
  const HalfedgeHandle h0{int(2 * edge)}, h1{int(2 * edge + 1)};
  const VertexHandle a = m_.to_vertex_handle(h1), b = m_.to_vertex_handle(h0);
  const auto& da = s_.vd[size_t(a.idx())];
  const auto& db = s_.vd[size_t(b.idx())];
  const VertexClass ca = da.cls, cb = db.cls;
  // Everything below is relative to a (the quadrics are stored relative to
  // their own vertex): b sits at t.
  const glm::dvec3 pa(da.p), t = glm::dvec3(db.p) - pa;
  const bool bothFree = ca == VertexClass::Free && cb == VertexClass::Free;
  if (!bothFree) {
    if (ca == VertexClass::Fixed && cb == VertexClass::Fixed) return false;
    const EdgeKind kind = s_.edgeKind(h0);
    const bool ra = removable(ca, kind), rb = removable(cb, kind);
    if (!ra && !rb) return false;
    const Quadric q = da.q.load() + db.q.load().translated(-t);
    const double inv = q.weight > 0 ? 1.0 / q.weight : 0.0;
    // A constrained vertex never moves: the one that goes lands on the one
    // that stays, so polylines keep original vertices only. A polyline
    // vertex that goes costs at least how far its polyline's new segment
    // passes from the input vertices it now stands for.
    auto errGoing = [&](VertexClass c, VertexHandle gone, VertexHandle stays, const glm::dvec3& at) {
      const double e = q.evaluate(at) * inv;
      if (c != VertexClass::BoundaryLine && c != VertexClass::SeamLine) return e;
      return std::max(e, s_.polylineErrorSq(uint32_t(gone.idx()), uint32_t(stays.idx())));
    };
    const double errA = ra ? errGoing(ca, a, b, t) : HUGE_VAL;  // a goes, stays at b
    const double errB = rb ? errGoing(cb, b, a, glm::dvec3(0.0)) : HUGE_VAL;
    if (!(std::min(errA, errB) < HUGE_VAL)) return false;
    if (errA <= errB)
      plan.h = h0, plan.p = pa + t, plan.errSq = errA;
    else
      plan.h = h1, plan.p = pa, plan.errSq = errB;
    plan.moves = false;
    plan.key = float(plan.errSq + s_.lengthWeight * glm::dot(t, t));
    return true;
  }
  const Quadric q = da.q.load() + db.q.load().translated(-t);
  const double len2 = glm::dot(t, t);
  glm::dvec3 p;
  const double cost = placeOnEdge(q, glm::dvec3(0.0), t, p);
  plan.h = h0;
  plan.p = pa + p;
  plan.moves = true;
  plan.errSq = q.weight > 0 ? cost / q.weight : 0.0;
  // The small length term orders the many zero-error collapses of flat
  // areas shortest-first, which keeps triangles there well shaped; against
  // any real curvature it is negligible.
  plan.key = float(plan.errSq + s_.lengthWeight * len2);
  return true;
}

bool CollapseEngine::entryFor(uint32_t edge, Entry& out) const {
  if (s_.estate[edge] & kGone) return false;
  const HalfedgeHandle h0{int(2 * edge)};
  if (!mayTouch(m_.to_vertex_handle(h0)) || !mayTouch(m_.from_vertex_handle(h0))) return false;
  Plan plan;
  if (!evaluate(edge, plan) || plan.errSq > s_.maxErrorSq) return false;
  out = Entry::make(plan.key, edge);
  return true;
}

// A 4-ary heap: half the depth of a binary one, and the four children share
// a cache line, which is where a decimator's time goes at scale.
void CollapseEngine::siftDown(size_t i) {
  const size_t n = heap_.size();
  Entry* h = heap_.data();
  const Entry e = h[i];
  for (;;) {
    const size_t c0 = 4 * i + 1;
    if (c0 >= n) break;
    size_t best;
    if (c0 + 4 <= n) {
      // All four children: a branch-free minimum (the comparisons are
      // unpredictable, and mispredictions were most of the heap's time).
      const size_t a = c0 + (h[c0 + 1].packed < h[c0].packed);
      const size_t b = c0 + 2 + (h[c0 + 3].packed < h[c0 + 2].packed);
      best = h[b].packed < h[a].packed ? b : a;
    } else {
      best = c0;
      for (size_t c = c0 + 1; c < n; ++c)
        if (before(h[c], h[best])) best = c;
    }
    if (!before(h[best], e)) break;
    h[i] = h[best];
    i = best;
  }
  h[i] = e;
}

void CollapseEngine::siftUp(size_t i) {
  const Entry e = heap_[i];
  while (i > 0) {
    const size_t parent = (i - 1) / 4;
    if (!before(e, heap_[parent])) break;
    heap_[i] = heap_[parent];
    i = parent;
  }
  heap_[i] = e;
}

void CollapseEngine::removeTop() {
  heap_[0] = heap_.back();
  heap_.pop_back();
  if (!heap_.empty()) siftDown(0);
}

void CollapseEngine::popTop() {
  s_.estate[heap_[0].edge()] &= kGone;
  removeTop();
}

void CollapseEngine::compact() {
  // Entries of edges that collapses deleted would each cost a pop (a full
  // sift) to get rid of; once they are half the queue, one linear pass
  // drops them all (from the heap and from the entries waiting beside it)
  // and rebuilds the heap.
  auto dropGone = [&](EntryVector& v) {
    size_t n = 0;
    for (const Entry& e : v) {
      if (s_.estate[e.edge()] & kGone)
        s_.estate[e.edge()] = kGone;
      else
        v[n++] = e;
    }
    v.resize(n);
  };
  dropGone(heap_);
  dropGone(rest_);
  heapify();
  tombstones_ = 0;
}

void CollapseEngine::heapify() {
  for (size_t i = heap_.size() / 4 + 1; i-- > 0;)
    if (i < heap_.size()) siftDown(i);
}

void CollapseEngine::push(const Entry& e) {
  s_.estate[e.edge()] = kQueued;
  if (e.packed > restAbove_) {
    rest_.push_back(e);  // beyond this round: waits unsorted
    return;
  }
  heap_.push_back(e);
  siftUp(heap_.size() - 1);
}

void CollapseEngine::seedRange(uint32_t begin, uint32_t end, EntryVector&& taken) {
  EntryVector entries = std::move(taken);
  stats_.evaluations += evaluateUnqueued(begin, end, entries);
  seedEntries(std::move(entries));
}

void CollapseEngine::seedAround(std::span<const uint32_t> vertices, EntryVector&& taken, float keyLimit) {
  EntryVector entries = std::move(taken);
  std::vector<uint32_t> seen;
  Entry entry;
  for (const uint32_t v : vertices) {
    const HalfedgeHandle start = m_.halfedge_handle(VertexHandle(int(v)));
    if (!start.is_valid()) continue;
    HalfedgeHandle it = start;
    do {
      // The face's three edges: the two at v and the one across from it
      // (an edge its engine dropped because v was not its own).
      if (!m_.is_boundary(it))
        for (HalfedgeHandle h = it, e = it;;) {
          const uint32_t edge = uint32_t(h.idx()) >> 1;
          const uint8_t state = s_.estate[edge];
          // Only edges with both ends this engine's are looked at (and
          // marked): nobody else writes their state.
          if (!(state & (kQueued | kGone | kSeen)) && mayTouch(m_.to_vertex_handle(h)) &&
              mayTouch(m_.from_vertex_handle(h))) {
            s_.estate[edge] = kSeen;
            seen.push_back(edge);
            ++stats_.evaluations;
            if (entryFor(edge, entry)) entries.push_back(entry);
          }
          h = m_.next_halfedge_handle(h);
          if (h == e) break;
        }
      it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
    } while (it != start);
  }
  for (const uint32_t edge : seen) s_.estate[edge] &= uint8_t(~kSeen);
  adopt(std::move(entries));
  if (keyLimit < HUGE_VALF && heap_.size() > kSplitMin)
    splitAt(Entry::make(keyLimit, UINT32_MAX).packed);
  else
    heapify();
}

size_t CollapseEngine::evaluateUnqueued(uint32_t begin, uint32_t end, EntryVector& out) const {
  size_t evaluated = 0;
  Entry e;
  // Room for every edge of the range at once: grown by doubling, a queue
  // of millions (the last region's) was copied into fresh pages at every
  // doubling, each of them a first touch. Capacity that stays unused is
  // never touched.
  out.reserve(out.size() + (end - begin));
  for (uint32_t edge = begin; edge < end; ++edge) {
    const uint8_t state = s_.estate[edge];
    if (state & kGone) {
      s_.estate[edge] = kGone;  // a queue's entry of it, if any, was dropped with that queue
      continue;
    }
    if (state & kQueued) continue;  // taken over from the queue that holds it
    s_.estate[edge] = 0;
    ++evaluated;
    if (entryFor(edge, e)) out.push_back(e);
  }
  return evaluated;
}

void CollapseEngine::adopt(EntryVector&& entries) {
  heap_ = std::move(entries);
  rest_.clear();
  restAbove_ = UINT64_MAX;
  // |=: entries taken over from the regions' queues may be dirty (their
  // keys stale), and stay so until they reach the top.
  for (const Entry& e : heap_) s_.estate[e.edge()] |= kQueued;
}

void CollapseEngine::seedEntries(EntryVector&& entries, size_t heapTarget) {
  adopt(std::move(entries));
  if (heapTarget < heap_.size() / 2) {
    // The split: the heapTarget-th smallest of a sample (deterministic).
    const size_t stride = std::max<size_t>(1, heap_.size() / 65536);
    std::vector<uint64_t> sample;
    sample.reserve(heap_.size() / stride + 1);
    for (size_t i = stride / 2; i < heap_.size(); i += stride) sample.push_back(heap_[i].packed);
    const size_t k = std::min(sample.size() - 1, heapTarget / stride);
    std::nth_element(sample.begin(), sample.begin() + long(k), sample.end());
    splitAt(sample[k]);
    return;
  }
  heapify();
}

void CollapseEngine::splitAt(uint64_t bound) {
  // Entries above `bound` leave the heap for rest_ (unsorted), wherever
  // they were; those at or below it come back from rest_. One linear pass
  // over each, then one heapify of what the heap holds. The heap is
  // compacted in place and rest_ rebuilt in a scratch vector kept between
  // calls (a round starts with one of these in every region).
  scratch_.clear();
  // Room for the worst case up front, as in evaluateUnqueued: the first
  // split of a large queue grew these by doubling into fresh pages.
  scratch_.reserve(heap_.size() + rest_.size());
  heap_.reserve(heap_.size() + rest_.size());
  auto gone = [&](const Entry& e) {
    if (!(s_.estate[e.edge()] & kGone)) return false;
    s_.estate[e.edge()] = kGone;  // a queued entry of a deleted edge: dropped here
    tombstones_ -= std::min<size_t>(tombstones_, 1);
    return true;
  };
  size_t n = 0;
  for (const Entry& e : heap_) {
    if (gone(e)) continue;
    if (e.packed <= bound)
      heap_[n++] = e;
    else
      scratch_.push_back(e);
  }
  heap_.resize(n);
  for (const Entry& e : rest_) {
    if (gone(e)) continue;
    if (e.packed <= bound)
      heap_.push_back(e);
    else
      scratch_.push_back(e);
  }
  std::swap(rest_, scratch_);
  restAbove_ = rest_.empty() ? UINT64_MAX : bound;
  heapify();
}

void CollapseEngine::takeLiveEntries(EntryVector& out) {
  if (out.empty()) {
    std::swap(out, heap_);
    size_t n = 0;
    for (const Entry& e : out)
      if (!(s_.estate[e.edge()] & kGone)) out[n++] = e;
    out.resize(n);
  } else {
    for (const Entry& e : heap_)
      if (!(s_.estate[e.edge()] & kGone)) out.push_back(e);
  }
  for (const Entry& e : rest_)
    if (!(s_.estate[e.edge()] & kGone)) out.push_back(e);
  heap_.clear(), rest_.clear();
}

bool CollapseEngine::topologyOk(const Plan& plan) {
  // OpenMesh's TriConnectivity::is_collapse_ok, with the one-ring test done
  // on a small local list instead of status tags: tags would be writes to
  // shared vertices when regions run in parallel.
  const HalfedgeHandle h = plan.h, o = m_.opposite_halfedge_handle(h);
  const VertexHandle v0 = m_.to_vertex_handle(o), v1 = m_.to_vertex_handle(h);
  VertexHandle vl, vr;
  if (!m_.is_boundary(h)) {
    const HalfedgeHandle h1 = m_.next_halfedge_handle(h), h2 = m_.next_halfedge_handle(h1);
    vl = m_.to_vertex_handle(h1);
    if (m_.is_boundary(m_.opposite_halfedge_handle(h1)) && m_.is_boundary(m_.opposite_halfedge_handle(h2)))
      return false;
  }
  if (!m_.is_boundary(o)) {
    const HalfedgeHandle o1 = m_.next_halfedge_handle(o), o2 = m_.next_halfedge_handle(o1);
    vr = m_.to_vertex_handle(o1);
    if (m_.is_boundary(m_.opposite_halfedge_handle(o1)) && m_.is_boundary(m_.opposite_halfedge_handle(o2)))
      return false;
  }
  if (vl == vr) return false;
  if (m_.is_boundary(v0) && m_.is_boundary(v1) && !m_.is_boundary(h) && !m_.is_boundary(o)) return false;

  // One-ring of v0 in a stack array (the vector only for huge valences).
  int local[32];
  int* ring = local;
  size_t n = 0;
  ring_.clear();
  const HalfedgeHandle s0 = m_.halfedge_handle(v0);
  HalfedgeHandle it = s0;
  do {
    if (n == 32 && ring == local) ring_.assign(local, local + 32), ring = nullptr;
    if (ring)
      ring[n] = m_.to_vertex_handle(it).idx();
    else
      ring_.push_back(m_.to_vertex_handle(it).idx());
    ++n;
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != s0);
  const int* first = ring ? ring : ring_.data();
  const HalfedgeHandle s1 = m_.halfedge_handle(v1);
  it = s1;
  do {
    const VertexHandle x = m_.to_vertex_handle(it);
    if (x != vl && x != vr && std::find(first, first + n, x.idx()) != first + n) return false;
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != s1);
  return true;
}

bool CollapseEngine::geometryOk(const Plan& plan) {
  const HalfedgeHandle h = plan.h, o = m_.opposite_halfedge_handle(h);
  const VertexHandle v0 = m_.to_vertex_handle(o), v1 = m_.to_vertex_handle(h);
  const FaceHandle fl = m_.face_handle(h), fr = m_.face_handle(o);
  const glm::dvec3 p = plan.p;
  const double cosMax = s_.cosMaxNormalDeviation, minQ = s_.minQuality;
  // Squared qualities (12|n|^2 / (sum l^2)^2, i.e. quality^2): the worst
  // face the collapse leaves and the worst it changes or removes.
  double worstNew = HUGE_VAL, worstOld = HUGE_VAL;
  auto quality2 = [](double nSq, double lSq) { return lSq > 0 ? 12.0 * nSq / (lSq * lSq) : 0.0; };
  auto edgesSq = [](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return glm::dot(b - a, b - a) + glm::dot(c - a, c - a) + glm::dot(b - c, b - c);
  };
  // 0 = fine, 1 = a face turns too far, 2 = a sliver appears
  auto check = [&](VertexHandle v) -> int {
    const glm::dvec3 pv = s_.point(v.idx());
    const HalfedgeHandle start = m_.halfedge_handle(v);
    HalfedgeHandle it = start;
    do {
      const FaceHandle f = m_.face_handle(it);
      if (f.is_valid() && f != fl && f != fr) {
        const glm::dvec3 pb = s_.point(m_.to_vertex_handle(it).idx());
        const glm::dvec3 pc = s_.point(m_.to_vertex_handle(m_.next_halfedge_handle(it)).idx());
        const glm::dvec3 nOld = glm::cross(pb - pv, pc - pv);
        const glm::dvec3 nNew = glm::cross(pb - p, pc - p);
        const double newSq = glm::dot(nNew, nNew), oldSq = glm::dot(nOld, nOld);
        if (!(newSq > 0)) return 2;
        // Normal turn: dot < cos * |old| |new|, compared squared (no sqrt).
        if (oldSq > 0) {
          const double d = glm::dot(nNew, nOld);
          const double bound = cosMax * cosMax * newSq * oldSq;
          if (cosMax >= 0 ? (d < 0 || d * d < bound) : (d < 0 && d * d > bound)) return 1;
        }
        worstNew = std::min(worstNew, quality2(newSq, edgesSq(p, pb, pc)));
        worstOld = std::min(worstOld, quality2(oldSq, edgesSq(pv, pb, pc)));
      }
      it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
    } while (it != start);
    return 0;
  };
  int r = check(v0);
  if (r == 0 && plan.moves) r = check(v1);  // v1's own faces change only if it moves
  // Slivers: refused when the worst face left is under minQuality and worse
  // than the worst face of the neighbourhood before (the faces changed and
  // the two removed). Comparing each face with its own old shape instead
  // refused every collapse that thinned any face of an already slivered
  // region (a graded or anisotropic scan): decimation then went elsewhere,
  // cost 1.4x meshopt's Hausdorff and flipped 35 faces on the generated
  // quad object (bench/decimate/README.md, "A quad-dominant object").
  if (r == 0) {
    for (const FaceHandle f : {fl, fr}) {
      if (!f.is_valid()) continue;
      const uint32_t* c = &s_.fv[size_t(f.idx()) * 3];
      const glm::dvec3 a = s_.point(int(c[0])), b = s_.point(int(c[1])), d = s_.point(int(c[2]));
      const glm::dvec3 n = glm::cross(b - a, d - a);
      worstOld = std::min(worstOld, quality2(glm::dot(n, n), edgesSq(a, b, d)));
    }
    if (worstNew < minQ * minQ && worstNew < worstOld) r = 2;
  }
  if (r == 1) ++stats_.rejectedFlip;
  if (r == 2) ++stats_.rejectedSliver;
  return r == 0;
}

bool CollapseEngine::wedgeMap(const Plan& plan, uint32_t (&from)[2], uint32_t (&to)[2], int& count) const {
  // Corners of the vertex that goes take the wedge the staying vertex has
  // on the same side of the collapsed edge; on a seam that is one wedge per
  // side. A corner with a wedge the edge's faces do not show would need a
  // wedge that does not exist: refuse.
  const HalfedgeHandle h = plan.h, o = m_.opposite_halfedge_handle(h);
  const uint32_t v0 = uint32_t(m_.to_vertex_handle(o).idx()), v1 = uint32_t(m_.to_vertex_handle(h).idx());
  count = 0;
  for (const FaceHandle f : {m_.face_handle(h), m_.face_handle(o)}) {
    if (!f.is_valid()) continue;
    const uint32_t w0 = s_.wedgeAt(uint32_t(f.idx()), v0), w1 = s_.wedgeAt(uint32_t(f.idx()), v1);
    if (count == 1 && from[0] == w0) {
      if (to[0] != w1) return false;
      continue;
    }
    from[count] = w0, to[count] = w1, ++count;
  }
  // A free vertex has one wedge by construction; only polyline vertices
  // (two wedges, one per side) need their fan checked.
  if (s_.vd[v0].cls == VertexClass::Free) return count > 0;
  const HalfedgeHandle start = m_.halfedge_handle(VertexHandle(int(v0)));
  HalfedgeHandle it = start;
  do {
    const FaceHandle f = m_.face_handle(it);
    if (f.is_valid()) {
      const uint32_t w = s_.wedgeAt(uint32_t(f.idx()), v0);
      if (!(count > 0 && from[0] == w) && !(count > 1 && from[1] == w)) return false;
    }
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != start);
  return count > 0;
}

glm::vec2 CollapseEngine::interpolateUv(const Plan& plan) const {
  // The texture coordinate of the surface point the moved vertex lands on:
  // barycentric in the face (of both fans, before the collapse) that
  // contains its projection best. Both ends are free, so the fans lie in
  // one chart and their corners' UVs are continuous. The two faces on the
  // edge are tried first: the new position is near the edge, and usually
  // inside one of them, which settles it without walking the fans.
  const HalfedgeHandle h = plan.h, o = m_.opposite_halfedge_handle(h);
  const glm::dvec3 p = plan.p;
  double bestScore = -HUGE_VAL;
  glm::dvec3 bestBary(1, 0, 0);
  uint32_t bestFace = UINT32_MAX;
  auto tryFace = [&](FaceHandle f) {
    if (!f.is_valid()) return;
    const uint32_t fi = uint32_t(f.idx());
    const glm::dvec3& a = s_.point(int(s_.fv[fi * 3 + 0]));
    const glm::dvec3 e0 = s_.point(int(s_.fv[fi * 3 + 1])) - a, e1 = s_.point(int(s_.fv[fi * 3 + 2])) - a, e2 = p - a;
    const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
    const double d20 = glm::dot(e2, e0), d21 = glm::dot(e2, e1);
    const double den = d00 * d11 - d01 * d01;
    if (!(den > 0)) return;
    const double bv = (d11 * d20 - d01 * d21) / den, bw = (d00 * d21 - d01 * d20) / den;
    const glm::dvec3 bary(1.0 - bv - bw, bv, bw);
    const double score = std::min(bary.x, std::min(bary.y, bary.z));
    if (score > bestScore) bestScore = score, bestBary = bary, bestFace = fi;
  };
  tryFace(m_.face_handle(h));
  tryFace(m_.face_handle(o));
  if (bestScore < 0)
    for (const VertexHandle v : {m_.to_vertex_handle(o), m_.to_vertex_handle(h)}) {
      const HalfedgeHandle start = m_.halfedge_handle(v);
      HalfedgeHandle it = start;
      do {
        tryFace(m_.face_handle(it));
        it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
      } while (it != start && bestScore < 0);
    }
  if (bestFace == UINT32_MAX) return s_.wedgeUv[s_.wedgeAt(uint32_t(m_.face_handle(h).idx()), uint32_t(m_.to_vertex_handle(h).idx()))];
  glm::dvec3 w = glm::max(bestBary, glm::dvec3(0.0));
  const double sum = w.x + w.y + w.z;
  w = sum > 0 ? w / sum : glm::dvec3(1, 0, 0);
  const glm::dvec2 uv = w.x * glm::dvec2(s_.wedgeUv[s_.fw[bestFace * 3 + 0]]) +
                        w.y * glm::dvec2(s_.wedgeUv[s_.fw[bestFace * 3 + 1]]) +
                        w.z * glm::dvec2(s_.wedgeUv[s_.fw[bestFace * 3 + 2]]);
  return glm::vec2(uv);
}

// OpenMesh's PolyConnectivity::collapse (collapse_edge + collapse_loop),
// same steps on the same kernel arrays, inlined, and with the search for a
// boundary outgoing halfedge (adjust_outgoing_halfedge: a walk around the
// whole vertex) done only for vertices that are on a boundary: for the
// rest any outgoing halfedge satisfies OpenMesh's invariant. That walk was
// a third of the collapse time.
void CollapseEngine::adjustOutgoing(VertexHandle v) {
  const HalfedgeHandle start = m_.halfedge_handle(v);
  if (!start.is_valid()) return;
  HalfedgeHandle it = start;
  do {
    if (m_.is_boundary(it)) {
      m_.set_halfedge_handle(v, it);
      return;
    }
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != start);
}

void CollapseEngine::collapseLoop(HalfedgeHandle h0, bool firstOnBoundary, bool secondOnBoundary) {
  const HalfedgeHandle h1 = m_.next_halfedge_handle(h0);
  const HalfedgeHandle o0 = m_.opposite_halfedge_handle(h0), o1 = m_.opposite_halfedge_handle(h1);
  const VertexHandle v0 = m_.to_vertex_handle(h0), v1 = m_.to_vertex_handle(h1);
  const FaceHandle fh = m_.face_handle(h0), fo = m_.face_handle(o0);
  m_.set_next_halfedge_handle(h1, m_.next_halfedge_handle(o0));
  m_.set_next_halfedge_handle(m_.prev_halfedge_handle(o0), h1);
  m_.set_face_handle(h1, fo);
  m_.set_halfedge_handle(v0, h1);
  if (firstOnBoundary) adjustOutgoing(v0);
  m_.set_halfedge_handle(v1, o1);
  if (secondOnBoundary) adjustOutgoing(v1);
  if (fo.is_valid() && m_.halfedge_handle(fo) == o0) m_.set_halfedge_handle(fo, h1);
  if (fh.is_valid()) {
    m_.set_halfedge_handle(fh, HalfedgeHandle());
    s_.faceStatus[fh.idx()].set_deleted(true);
  }
  s_.edgeStatus[h0.idx() >> 1].set_deleted(true);
  tombstones_ += s_.estate[h0.idx() >> 1] & kQueued;
  s_.estate[h0.idx() >> 1] |= kGone;
}

void CollapseEngine::halfedgeCollapse(HalfedgeHandle h) {
  const HalfedgeHandle hn = m_.next_halfedge_handle(h), hp = m_.prev_halfedge_handle(h);
  const HalfedgeHandle o = m_.opposite_halfedge_handle(h);
  const HalfedgeHandle on = m_.next_halfedge_handle(o), op = m_.prev_halfedge_handle(o);
  const FaceHandle fh = m_.face_handle(h), fo = m_.face_handle(o);
  const VertexHandle vh = m_.to_vertex_handle(h), vo = m_.to_vertex_handle(o);
  // Boundary status before: the kept vertex ends on a boundary if either
  // end was on one; the two opposite vertices keep theirs.
  const bool vhBoundary = m_.is_boundary(vh) || m_.is_boundary(vo);
  const VertexHandle vl = fh.is_valid() ? m_.to_vertex_handle(hn) : VertexHandle();
  const VertexHandle vr = fo.is_valid() ? m_.to_vertex_handle(on) : VertexHandle();
  const bool vlBoundary = vl.is_valid() && m_.is_boundary(vl);
  const bool vrBoundary = vr.is_valid() && m_.is_boundary(vr);

  // collapse_edge: every halfedge into vo now ends at vh.
  const HalfedgeHandle start = m_.halfedge_handle(vo);
  HalfedgeHandle it = start;
  do {
    m_.set_vertex_handle(m_.opposite_halfedge_handle(it), vh);
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != start);
  m_.set_next_halfedge_handle(hp, hn);
  m_.set_next_halfedge_handle(op, on);
  if (fh.is_valid()) m_.set_halfedge_handle(fh, hn);
  if (fo.is_valid()) m_.set_halfedge_handle(fo, on);
  if (m_.halfedge_handle(vh) == o) m_.set_halfedge_handle(vh, hn);
  if (vhBoundary) adjustOutgoing(vh);
  m_.set_isolated(vo);
  s_.edgeStatus[h.idx() >> 1].set_deleted(true);
  s_.vertexStatus[vo.idx()].set_deleted(true);
  tombstones_ += s_.estate[h.idx() >> 1] & kQueued;
  s_.estate[h.idx() >> 1] |= kGone;

  // The two faces beside the edge are now two-edge loops: remove them.
  if (m_.next_halfedge_handle(m_.next_halfedge_handle(hn)) == hn)
    collapseLoop(m_.next_halfedge_handle(hn), vhBoundary, vlBoundary);
  if (m_.next_halfedge_handle(m_.next_halfedge_handle(on)) == on)
    collapseLoop(on, vrBoundary, vhBoundary);
}

void CollapseEngine::collapse(const Plan& plan, const uint32_t (&from)[2], const uint32_t (&to)[2], int count,
                              size_t& liveFaces) {
  const HalfedgeHandle h = plan.h, o = m_.opposite_halfedge_handle(h);
  const VertexHandle v0 = m_.to_vertex_handle(o), v1 = m_.to_vertex_handle(h);
  const bool setUv = plan.moves && !s_.wedgeUv.empty();
  const glm::vec2 uv = setUv ? interpolateUv(plan) : glm::vec2(0.0f);
  liveFaces -= size_t(m_.face_handle(h).is_valid()) + size_t(m_.face_handle(o).is_valid());

  // The kept vertex's quadric (both ends' sum) moves to its new place,
  // which is where it is stored relative to from now on.
  {
    auto& d1 = s_.vd[size_t(v1.idx())];
    const glm::vec3 pf(plan.p);
    const Quadric q = s_.quadricAt(size_t(v1.idx()), size_t(v0.idx()), glm::dvec3(pf));
    d1.q = QuadricF::store(q);
    if (plan.moves) {
      d1.p = pf;
      // The output's copy, in double: the place the solve chose, not its
      // float rounding (61 um at 500 m from the centre).
      m_.point(v1) = OpenMesh::Vec3d(plan.p.x, plan.p.y, plan.p.z);
    }
  }
  halfedgeCollapse(h);
  if (setUv) s_.wedgeUv[to[0]] = uv;  // a free vertex has one wedge

  // The fan of v1 now holds v0's faces: rename their corners, then refresh
  // the cost of every edge around v1 (its quadric and position changed).
  const uint32_t v0i = uint32_t(v0.idx()), v1i = uint32_t(v1.idx());
  const HalfedgeHandle start = m_.halfedge_handle(v1);
  HalfedgeHandle it = start;
  do {
    const FaceHandle f = m_.face_handle(it);
    if (f.is_valid()) {
      const size_t base = size_t(f.idx()) * 3;
      for (size_t k = 0; k < 3; ++k)
        if (s_.fv[base + k] == v0i) {
          s_.fv[base + k] = v1i;
          s_.fw[base + k] = (count > 1 && s_.fw[base + k] == from[1]) ? to[1] : to[0];
        }
    }
    const VertexHandle x = m_.to_vertex_handle(it);
    if (mayTouch(x)) {
      const uint32_t e = uint32_t(it.idx()) >> 1;
      Entry entry;
      if (s_.estate[e] & kQueued)
        s_.estate[e] |= kDirty;  // re-evaluated if and when it reaches the top
      else if (++stats_.evaluations, entryFor(e, entry))
        push(entry), ++stats_.pushed;            // was refused before; the new neighbourhood may allow it
    }
    it = m_.next_halfedge_handle(m_.opposite_halfedge_handle(it));
  } while (it != start);
}

void CollapseEngine::sampleKeys(size_t stride, std::vector<float>& out) const {
  // Entries of deleted edges are skipped: they are most of a busy queue's
  // low keys (edges beside cheap collapses), and counting them set the
  // thresholds far too low (100 rounds at 50% on the scan tile).
  // Starting mid-stride: index 0 is the queue's minimum, and with 64
  // queues their 64 minima, each standing for `stride` entries, were the
  // whole low end of the sample (thresholds crept up by one collapse a
  // region per round). The heap and the entries waiting beside it are one
  // queue: sampled as one sequence.
  const size_t n = heap_.size() + rest_.size();
  for (size_t i = stride / 2; i < n; i += stride) {
    const Entry& e = i < heap_.size() ? heap_[i] : rest_[i - heap_.size()];
    if (!(s_.estate[e.edge()] & kGone)) out.push_back(e.key());
  }
}

// The next top is one of the root's children, or after a pop or a sink
// one of theirs, and its evaluation waits on a chain of loads (heap entry
// -> halfedges' to-vertex -> two vertex records; 65% of evaluate's samples
// sat on them). Two levels ahead, so that no prefetch waits on another:
// the grandchildren's halfedges and state bytes are requested now, the
// children's records from halfedges requested a top or two ago. It reads
// only halfedges of edges in this engine's own queue (which no other
// engine rewrites, deleted ones included) and hints at their vertices'
// records, so it adds no sharing between regions and changes no result.
// (Prefetching one level, the children's halfedges, was
// inside the noise in the fourth round; two levels took 9% of the CPU on
// the 2M tile at 10%, see docs/meshes.md, "Sixth round".)
void CollapseEngine::prefetchNext() const {
  const size_t n = heap_.size();
  for (size_t c = 1; c < std::min<size_t>(n, 5); ++c) {
    const uint32_t e = heap_[c].edge();
    const int a = m_.to_vertex_handle(HalfedgeHandle{int(2 * e + 1)}).idx();
    const int b = m_.to_vertex_handle(HalfedgeHandle{int(2 * e)}).idx();
    __builtin_prefetch(&s_.vd[size_t(a)]);
    __builtin_prefetch(&s_.vd[size_t(b)]);
  }
  for (size_t g = 5; g < std::min<size_t>(n, 21); ++g) {
    const uint32_t e = heap_[g].edge();
    __builtin_prefetch(&m_.halfedge(HalfedgeHandle{int(2 * e)}));
    __builtin_prefetch(&s_.estate[e]);
  }
}

bool CollapseEngine::run(size_t& liveFacesOut, size_t targetFaces, float keyLimit, const Progress* progress,
                         std::atomic<size_t>& done, size_t expectedTotal, bool reporter) {
  // A local count: regions' counters sit side by side in one array, and
  // updating them in place from two threads would share cache lines.
  size_t liveFaces = liveFacesOut;
  struct WriteBack {
    size_t& from;
    size_t& to;
    ~WriteBack() { to = from; }
  } writeBack{liveFaces, liveFacesOut};
  size_t sinceReport = 0;
  // Only entries up to this round's limit need an order: the heap keeps
  // those, and the rest waits unsorted beside it (rest_) until a later
  // round's limit reaches it. The heap then holds a round's worth of
  // entries instead of the whole queue (the sifts were the largest item of
  // the loop's profile, and waited on a queue that outgrew the cache), and
  // an entry whose key grows past the limit leaves it without a sift. The
  // collapses come in the same order as from one heap: the heap's top is
  // the smallest entry as long as it is at or below restAbove_.
  const uint64_t limitPacked = keyLimit < HUGE_VALF ? Entry::make(keyLimit, UINT32_MAX).packed : UINT64_MAX;
  if (limitPacked < restAbove_ && heap_.size() + rest_.size() > kSplitMin) splitAt(limitPacked);
  for (;;) {
    if (liveFaces <= targetFaces) break;
    if (!rest_.empty() && (heap_.empty() || heap_[0].packed > restAbove_)) {
      if (restAbove_ >= limitPacked) break;  // what waits is beyond this round
      splitAt(limitPacked);
    }
    if (heap_.empty() || heap_[0].key() > keyLimit) break;
    prefetchNext();
    const uint32_t edge = heap_[0].edge();
    ++stats_.tops;
    const uint8_t state = s_.estate[edge];
    if (state & kGone) {
      ++stats_.deletedTops;
      popTop();
      continue;
    }
    Plan plan;
    ++stats_.evaluations;
    if (!evaluate(edge, plan) || plan.errSq > s_.maxErrorSq) {
      popTop();
      continue;
    }
    if (state & kDirty) {
      s_.estate[edge] = kQueued;
      // Still no later than the next best entry: it stays first, go on;
      // otherwise it sinks to where its new key belongs.
      const Entry fresh = Entry::make(plan.key, edge);
      // (Every entry waiting beside the heap is above restAbove_: past it,
      // the fresh key may be behind one of those.)
      bool stays = fresh.packed <= restAbove_;
      for (size_t c = 1; c < std::min<size_t>(5, heap_.size()); ++c) stays &= before(fresh, heap_[c]);
      if (!stays) {
        ++stats_.sank;
        if (fresh.packed > restAbove_) {
          // Past what the heap holds: it waits with the rest (still queued).
          rest_.push_back(fresh);
          removeTop();
          continue;
        }
        heap_[0] = fresh;
        siftDown(0);
        continue;
      }
    }
    popTop();
    if (region_ != kSharedRegion) {
      // The faces beyond the two that vanish get rewired too: their third
      // vertices must be ours as well, or the edge waits for a later level.
      const HalfedgeHandle o = m_.opposite_halfedge_handle(plan.h);
      if ((!m_.is_boundary(plan.h) && !mayTouch(m_.to_vertex_handle(m_.next_halfedge_handle(plan.h)))) ||
          (!m_.is_boundary(o) && !mayTouch(m_.to_vertex_handle(m_.next_halfedge_handle(o))))) {
        ++stats_.notOurs;
        continue;
      }
    }
    uint32_t from[2], to[2];
    int count = 0;
    if (!topologyOk(plan) || !wedgeMap(plan, from, to, count)) {
      ++stats_.rejectedTopology;
      continue;
    }
    if (!geometryOk(plan)) continue;
    collapse(plan, from, to, count, liveFaces);
    if (tombstones_ * 2 > heap_.size() + rest_.size()) compact(), ++stats_.compactions;
    ++stats_.collapses;
    stats_.maxErrorSq = std::max(stats_.maxErrorSq, plan.errSq);
    if (++sinceReport == 1024) {
      const size_t total = done.fetch_add(sinceReport) + sinceReport;
      sinceReport = 0;
      if (isCancelled(progress)) return false;
      if (reporter && expectedTotal)
        reportProgress(progress, 0.1 + 0.8 * std::min(1.0, double(total) / double(expectedTotal)), "Decimating");
    }
  }
  stoppedAtTarget_ = liveFaces <= targetFaces;
  done.fetch_add(sinceReport);
  return !isCancelled(progress);
}

}  // namespace hs::mesh
