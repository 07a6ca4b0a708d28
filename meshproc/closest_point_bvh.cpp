#include "meshproc/closest_point_bvh.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.h"
#include "mesh/radix_sort.h"

namespace hs::mesh {
namespace {

// Squared distance between the box [l, h] and the box [lo, hi] (a point
// where lo == hi): every lower bound the queries prune with.
inline double boxGapSq(const float l[3], const float h[3], const glm::dvec3& lo, const glm::dvec3& hi) {
  double d = 0;
  for (int a = 0; a < 3; ++a) {
    const double la = double(l[a]), ha = double(h[a]);
    const double e = hi[a] < la ? la - hi[a] : lo[a] > ha ? lo[a] - ha : 0.0;
    d += e * e;
  }
  return d;
}

}  // namespace

double closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, glm::dvec3& closest, glm::dvec3& bary) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  auto done = [&](const glm::dvec3& w) {
    bary = w;
    closest = w.x * a + w.y * b + w.z * c;
    const glm::dvec3 d = p - closest;
    return glm::dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0) return done({1, 0, 0});
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return done({0, 1, 0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return done({1 - v, v, 0});
  }
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return done({0, 0, 1});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return done({1 - w, 0, w});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return done({0, 1 - w, w});
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) {
    // Degenerate (zero-area) triangle: the nearest of its three edges.
    glm::dvec3 bestPoint, bestBary;
    double best = HUGE_VAL;
    const glm::dvec3 v[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3 s = v[e], t = v[(e + 1) % 3], st = t - s;
      const double len2 = glm::dot(st, st);
      const double u = len2 > 0 ? std::clamp(glm::dot(p - s, st) / len2, 0.0, 1.0) : 0.0;
      const glm::dvec3 q = s + u * st;
      const double d = glm::dot(p - q, p - q);
      if (d < best) {
        best = d, bestPoint = q;
        bestBary = glm::dvec3(0.0);
        bestBary[e] = 1 - u;
        bestBary[(e + 1) % 3] = u;
      }
    }
    closest = bestPoint, bary = bestBary;
    return best;
  }
  const double v = vb / denom, w = vc / denom;
  return done({1 - v - w, v, w});
}

ClosestPointBvh::ClosestPointBvh(const MeshData& mesh, unsigned threads) {
  const size_t nf = mesh.triangleCount();
  if (nf == 0) return;
  const auto& pos = mesh.positions;
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const auto& p : pos) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 scale = 1023.0f / glm::max(hi - lo, glm::vec3(1e-30f));
  std::vector<uint64_t> order(nf);
  parallelRanges(nf, resolveThreads(threads), [&](size_t b, size_t e, unsigned) {
    for (size_t f = b; f < e; ++f) {
      const glm::vec3 c = (pos[mesh.indices[f * 3]] + pos[mesh.indices[f * 3 + 1]] + pos[mesh.indices[f * 3 + 2]]) / 3.0f;
      const glm::uvec3 q = glm::uvec3(glm::clamp((c - lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f)));
      order[f] = (uint64_t(mortonCode10(q.x, q.y, q.z)) << 32) | f;
    }
  });
  radixSortByKey(order, 30, resolveThreads(threads));
  std::vector<uint32_t> codes(nf);
  faceOfSlot_.resize(nf);
  slotOfFace_.resize(nf);
  tris_.resize(nf);
  for (size_t s = 0; s < nf; ++s) {
    const uint32_t f = uint32_t(order[s]);
    codes[s] = uint32_t(order[s] >> 32);
    faceOfSlot_[s] = f;
    slotOfFace_[f] = uint32_t(s);
    SlotTriangle& t = tris_[s];
    for (size_t k = 0; k < 3; ++k) t.v[k] = pos[mesh.indices[size_t(f) * 3 + k]];
    const glm::dvec3 a(t.v[0]), e1 = glm::dvec3(t.v[1]) - a, e2 = glm::dvec3(t.v[2]) - a;
    const glm::dvec3 c = glm::cross(e1, e2);
    const double len = glm::length(c);
    // The normal's direction is good to about 1e-16 |e1| |e2| / |c| in
    // double (then 6e-8 in float); kept where that is under 1e-8.
    t.n = len > 1e8 * 1e-16 * glm::length(e1) * glm::length(e2) && len > 0 ? glm::vec3(c / len) : glm::vec3(0.0f);
  }
  nodes_.reserve(nf / 2 + 16);
  nodes_.push_back({});
  build(0, 0, uint32_t(nf), codes, 29);
}

// Splits a Morton-sorted range where its highest differing bit changes
// (the octree cell boundary), or in the middle once the codes run out.
// Children are stored next to each other, so an inner node needs one index.
void ClosestPointBvh::build(uint32_t slot, uint32_t begin, uint32_t end, const std::vector<uint32_t>& codes, int bit) {
  constexpr uint32_t kLeafSize = 4;
  Node n{};
  if (end - begin <= kLeafSize) {
    n.first = begin, n.count = end - begin;
    for (int a = 0; a < 3; ++a) n.lo[a] = HUGE_VALF, n.hi[a] = -HUGE_VALF;
    for (uint32_t s = begin; s < end; ++s)
      for (const glm::vec3& v : tris_[s].v)
        for (int a = 0; a < 3; ++a) n.lo[a] = std::min(n.lo[a], v[a]), n.hi[a] = std::max(n.hi[a], v[a]);
    nodes_[slot] = n;
    return;
  }
  uint32_t split = begin + (end - begin) / 2;
  for (; bit >= 0; --bit) {
    const uint32_t mask = 1u << bit;
    if ((codes[begin] & mask) != (codes[end - 1] & mask)) {
      // Codes are sorted, so the ones with the bit set form the upper run.
      split = uint32_t(std::partition_point(codes.begin() + begin, codes.begin() + end,
                                            [&](uint32_t c) { return !(c & mask); }) - codes.begin());
      break;
    }
  }
  const uint32_t left = uint32_t(nodes_.size());
  nodes_.push_back({});
  nodes_.push_back({});
  build(left, begin, split, codes, bit - 1);
  build(left + 1, split, end, codes, bit - 1);
  n.first = left, n.count = 0;
  for (int a = 0; a < 3; ++a) {
    n.lo[a] = std::min(nodes_[left].lo[a], nodes_[left + 1].lo[a]);
    n.hi[a] = std::max(nodes_[left].hi[a], nodes_[left + 1].hi[a]);
  }
  nodes_[slot] = n;
}

void ClosestPointBvh::testSlot(uint32_t slot, const glm::dvec3& q, Hit& best) const {
  const SlotTriangle& t = tris_[slot];
  // Two lower bounds of the distance before the exact test, each a few
  // multiplications against its dozens: the distance from the triangle's
  // plane, which rejects the neighbours of the nearest triangle on a
  // curved surface (their boxes hold the point as well), and from its box.
  // The plane's is made smaller by what the float normal (1e-6 of the
  // distance from the corner, with room to spare) and the double rounding
  // of the exact test (1e-12 of the coordinates) could hide, so a triangle
  // at the best distance, a tie, is never rejected.
  const glm::dvec3 qa = q - glm::dvec3(t.v[0]);
  const double plane = std::abs(glm::dot(glm::dvec3(t.n), qa)) -
                       1e-6 * (std::abs(qa.x) + std::abs(qa.y) + std::abs(qa.z)) -
                       1e-12 * (std::abs(q.x) + std::abs(q.y) + std::abs(q.z)) - 1e-12;
  if (plane > 0 && plane * plane > best.distanceSq) return;
  float l[3], h[3];
  for (int a = 0; a < 3; ++a)
    l[a] = std::min({t.v[0][a], t.v[1][a], t.v[2][a]}), h[a] = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
  if (boxGapSq(l, h, q, q) > best.distanceSq) return;
  glm::dvec3 point, bary;
  const double d = closestPointOnTriangle(q, glm::dvec3(t.v[0]), glm::dvec3(t.v[1]), glm::dvec3(t.v[2]), point, bary);
  if (d < best.distanceSq || (d == best.distanceSq && faceOfSlot_[slot] < best.face)) {
    best.distanceSq = d;
    best.face = faceOfSlot_[slot];
    best.point = point;
    best.bary = bary;
  }
}

ClosestPointBvh::Hit ClosestPointBvh::closest(const glm::dvec3& q, uint32_t hintFace) const {
  return walk<false>(q, hintFace, 0.0);
}

ClosestPointBvh::Hit ClosestPointBvh::closestUnless(const glm::dvec3& q, uint32_t hintFace, double stopSq) const {
  return walk<true>(q, hintFace, stopSq);
}

template <bool kStop>
ClosestPointBvh::Hit ClosestPointBvh::walk(const glm::dvec3& q, uint32_t hintFace, double stopSq) const {
  Hit best;
  if (nodes_.empty()) return best;
  if (hintFace < slotOfFace_.size()) testSlot(slotOfFace_[hintFace], q, best);
  if (kStop && best.distanceSq < stopSq) return best;
  auto boxDistSq = [&](const Node& n) { return boxGapSq(n.lo, n.hi, q, q); };
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (boxDistSq(n) > best.distanceSq) continue;
    if (n.count > 0) {
      for (uint32_t s = n.first; s < n.first + n.count; ++s) testSlot(s, q, best);
      if (kStop && best.distanceSq < stopSq) return best;
      continue;
    }
    const double dl = boxDistSq(nodes_[n.first]), dr = boxDistSq(nodes_[n.first + 1]);
    // Push the farther child first so the nearer one is searched first.
    if (dl <= dr) {
      if (dr <= best.distanceSq) stack[top++] = n.first + 1;
      if (dl <= best.distanceSq) stack[top++] = n.first;
    } else {
      if (dl <= best.distanceSq) stack[top++] = n.first;
      if (dr <= best.distanceSq) stack[top++] = n.first + 1;
    }
  }
  return best;
}

uint32_t ClosestPointBvh::closestMany(std::span<const glm::dvec3> points, uint32_t hintFace, std::span<Hit> hits,
                                      ManyScratch& scratch) const {
  const size_t n = points.size();
  if (n == 0) return hintFace;
  // Points in the order of a Morton curve through their box, so that each
  // is near the one before: the face's samples come in random order, and
  // on a face much larger than the target's triangles the hint from a
  // point across the face bounds nothing.
  std::vector<uint32_t>& order = scratch.order;
  order.resize(n);
  if (n > kOrderFrom) {
    glm::dvec3 lo = points[0], hi = points[0];
    for (size_t k = 1; k < n; ++k) lo = glm::min(lo, points[k]), hi = glm::max(hi, points[k]);
    const glm::dvec3 scale = 1023.0 / glm::max(hi - lo, glm::dvec3(1e-300));
    std::vector<uint64_t>& keys = scratch.keys;
    keys.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const glm::uvec3 c = glm::uvec3(glm::clamp((points[k] - lo) * scale, glm::dvec3(0.0), glm::dvec3(1023.0)));
      keys[k] = (uint64_t(mortonCode10(c.x, c.y, c.z)) << 32) | k;
    }
    std::sort(keys.begin(), keys.end());
    for (size_t k = 0; k < n; ++k) order[k] = uint32_t(keys[k]);
  } else {
    for (size_t k = 0; k < n; ++k) order[k] = uint32_t(k);
  }
  // Chunks of consecutive points along the curve: each is small, so few
  // leaves lie near it, however large the face.
  uint32_t hint = hintFace;
  for (size_t c0 = 0; c0 < n; c0 += kChunk) {
    const size_t c1 = std::min(n, c0 + kChunk);
    hint = closestChunk(points, std::span<const uint32_t>(order).subspan(c0, c1 - c0), hint, hits, scratch);
  }
  return hint;
}

uint32_t ClosestPointBvh::closestChunk(std::span<const glm::dvec3> points, std::span<const uint32_t> order,
                                       uint32_t hintFace, std::span<Hit> hits, ManyScratch& scratch) const {
  const size_t n = order.size();
  // Every point after the first by its own walk, hinted by the one before.
  auto walkEach = [&] {
    scratch.walkedChunks += n > 1;
    for (size_t i = 1; i < n; ++i) hits[order[i]] = closest(points[order[i]], hits[order[i - 1]].face);
    return hits[order[n - 1]].face;
  };
  hits[order[0]] = closest(points[order[0]], hintFace);
  if (n == 1 || !hits[order[0]].found()) return walkEach();
  // Every point is at most its distance from the first point's triangle
  // from its own nearest one, which then lies in a leaf within the largest
  // such distance of the points' box.
  const uint32_t seedSlot = slotOfFace_[hits[order[0]].face];
  double bound = hits[order[0]].distanceSq;
  glm::dvec3 lo = points[order[0]], hi = lo;
  for (size_t i = 1; i < n; ++i) {
    Hit& h = hits[order[i]];
    h = Hit{};
    testSlot(seedSlot, points[order[i]], h);
    bound = std::max(bound, h.distanceSq);
    lo = glm::min(lo, points[order[i]]), hi = glm::max(hi, points[order[i]]);
  }
  // The margin keeps a leaf whose box distance rounds a hair above the
  // bound it meets exactly.
  const double limit = bound * (1.0 + 1e-9) + 1e-300;
  std::vector<uint32_t>& leaves = scratch.leaves;
  leaves.clear();
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t i = stack[--top];
    const Node& nd = nodes_[i];
    if (boxGapSq(nd.lo, nd.hi, lo, hi) > limit) continue;
    if (nd.count > 0) {
      leaves.push_back(i);
      if (leaves.size() > kMaxLeaves) return walkEach();  // seeds are overwritten: same hits
      continue;
    }
    stack[top++] = nd.first + 1;
    stack[top++] = nd.first;
  }
  ++scratch.scannedChunks;
  // The leaves' boxes in double, one array per bound, so that each point's
  // box distances are a loop the compiler vectorises.
  const size_t nl = leaves.size();
  std::vector<double>& bx = scratch.boxes;
  bx.resize(nl * 7);
  double* lx = bx.data();
  double *ly = lx + nl, *lz = ly + nl, *hx = lz + nl, *hy = hx + nl, *hz = hy + nl, *dist = hz + nl;
  for (size_t j = 0; j < nl; ++j) {
    const Node& nd = nodes_[leaves[j]];
    lx[j] = nd.lo[0], ly[j] = nd.lo[1], lz[j] = nd.lo[2], hx[j] = nd.hi[0], hy[j] = nd.hi[1], hz[j] = nd.hi[2];
  }
  for (size_t i = 1; i < n; ++i) {
    const glm::dvec3& q = points[order[i]];
    Hit& best = hits[order[i]];
    // The point before is usually nearest to the same triangle: a tight
    // bound before the scan. Both triangles tried are not tried again.
    const uint32_t prevSlot = slotOfFace_[hits[order[i - 1]].face];
    if (prevSlot != seedSlot) testSlot(prevSlot, q, best);
    for (size_t j = 0; j < nl; ++j) {
      const double ex = std::max(0.0, std::max(lx[j] - q.x, q.x - hx[j]));
      const double ey = std::max(0.0, std::max(ly[j] - q.y, q.y - hy[j]));
      const double ez = std::max(0.0, std::max(lz[j] - q.z, q.z - hz[j]));
      dist[j] = ex * ex + ey * ey + ez * ez;
    }
    for (size_t j = 0; j < nl; ++j) {
      if (dist[j] > best.distanceSq) continue;
      const Node& nd = nodes_[leaves[j]];
      for (uint32_t s = nd.first; s < nd.first + nd.count; ++s)
        if (s != seedSlot && s != prevSlot) testSlot(s, q, best);
    }
  }
  return hits[order[n - 1]].face;
}

bool ClosestPointBvh::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tMin,
                               double tMax) const {
  if (nodes_.empty() || !(tMax >= tMin)) return false;
  const glm::dvec3 inv(1.0 / direction.x, 1.0 / direction.y, 1.0 / direction.z);
  // Slabs: the parameter interval where the segment is inside the box.
  auto hitsBox = [&](const Node& n) {
    double t0 = tMin, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
      double lo = (double(n.lo[a]) - origin[a]) * inv[a], hi = (double(n.hi[a]) - origin[a]) * inv[a];
      if (lo > hi) std::swap(lo, hi);
      if (std::isnan(lo) || std::isnan(hi)) {  // direction 0 along a: inside the slab or not at all
        if (origin[a] < double(n.lo[a]) || origin[a] > double(n.hi[a])) return false;
        continue;
      }
      t0 = std::max(t0, lo);
      t1 = std::min(t1, hi);
      if (t0 > t1) return false;
    }
    return true;
  };
  auto hitsTriangle = [&](uint32_t slot) {
    const glm::dvec3 a(tris_[slot].v[0]), b(tris_[slot].v[1]), c(tris_[slot].v[2]);
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return false;  // parallel, or a degenerate triangle
    const double invDet = 1.0 / det;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) * invDet;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) * invDet;
    if (v < 0.0 || u + v > 1.0) return false;
    const double t = glm::dot(e2, q) * invDet;
    return t >= tMin && t <= tMax;
  };
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!hitsBox(n)) continue;
    if (n.count > 0) {
      for (uint32_t s = n.first; s < n.first + n.count; ++s)
        if (hitsTriangle(s)) return true;
      continue;
    }
    stack[top++] = n.first;
    stack[top++] = n.first + 1;
  }
  return false;
}

}  // namespace hs::mesh
