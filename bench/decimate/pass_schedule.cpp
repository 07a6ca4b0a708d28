#include "pass_schedule.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <meshoptimizer.h>

#include "mesh/radix_sort.h"
#include "meshproc/quadric.h"

namespace hs::bench {
namespace {

using hs::mesh::placeOnEdge;
using hs::mesh::Quadric;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point& t) {
  const auto now = Clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

enum : uint8_t { kFree = 0, kBoundaryLine = 1, kFixed = 2 };

// CSR lists: the live faces around each vertex.
struct FaceLists {
  std::vector<uint32_t> offset, face;
  void build(const std::vector<uint32_t>& fv, const std::vector<uint8_t>& dead, size_t nv) {
    offset.assign(nv + 1, 0);
    const size_t nf = dead.size();
    for (size_t f = 0; f < nf; ++f)
      if (!dead[f])
        for (int k = 0; k < 3; ++k) ++offset[fv[f * 3 + k] + 1];
    for (size_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
    face.resize(offset[nv]);
    std::vector<uint32_t> fill(offset.begin(), offset.end() - 1);
    for (size_t f = 0; f < nf; ++f)
      if (!dead[f])
        for (int k = 0; k < 3; ++k) face[fill[fv[f * 3 + k]]++] = uint32_t(f);
  }
};

bool hasVertex(const uint32_t* t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

}  // namespace

hs::mesh::MeshData decimateInPasses(const hs::mesh::MeshData& in, size_t targetTriangles,
                                    const PassScheduleOptions& opt, PassScheduleStats& st) {
  auto clock = Clock::now();
  // Weld by exact position; positions in double relative to the box centre.
  const size_t nvIn = in.positions.size();
  std::vector<uint32_t> remap(nvIn);
  const size_t nv =
      meshopt_generateVertexRemap(remap.data(), nullptr, nvIn, in.positions.data(), nvIn, sizeof(glm::vec3));
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const glm::vec3& p : in.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  const glm::dvec3 center = 0.5 * (lo + hi);
  std::vector<glm::dvec3> pos(nv);
  for (size_t i = 0; i < nvIn; ++i) pos[remap[i]] = glm::dvec3(in.positions[i]) - center;
  std::vector<uint32_t> fv;
  fv.reserve(in.indices.size());
  for (size_t f = 0; f < in.indices.size() / 3; ++f) {
    const uint32_t a = remap[in.indices[f * 3]], b = remap[in.indices[f * 3 + 1]], c = remap[in.indices[f * 3 + 2]];
    if (a != b && b != c && a != c) fv.insert(fv.end(), {a, b, c});
  }
  const size_t nf = fv.size() / 3;
  std::vector<uint8_t> dead(nf, 0);
  FaceLists lists;
  lists.build(fv, dead, nv);

  // Quadrics as the setup builds them: sqrt(area)-weighted face planes, and
  // on each boundary edge a plane through it perpendicular to its face,
  // weighted by its length. (Absolute frame: fine at the bunny's size.)
  std::vector<Quadric> q(nv, Quadric{});
  std::vector<int> boundaryEdges(nv, 0);
  auto directedEdgeExists = [&](uint32_t a, uint32_t b) {
    for (uint32_t i = lists.offset[a]; i < lists.offset[a + 1]; ++i) {
      const uint32_t* t = &fv[size_t(lists.face[i]) * 3];
      for (int k = 0; k < 3; ++k)
        if (t[k] == a && t[(k + 1) % 3] == b) return true;
    }
    return false;
  };
  for (size_t f = 0; f < nf; ++f) {
    const uint32_t* t = &fv[f * 3];
    glm::dvec3 n = glm::cross(pos[t[1]] - pos[t[0]], pos[t[2]] - pos[t[0]]);
    const double len = glm::length(n);
    if (!(len > 0)) continue;
    n /= len;
    const Quadric face = Quadric::plane(n, -glm::dot(n, pos[t[0]]), std::sqrt(0.5 * len));
    for (int k = 0; k < 3; ++k) q[t[k]] += face;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      if (directedEdgeExists(b, a)) continue;
      ++boundaryEdges[a], ++boundaryEdges[b];
      const glm::dvec3 e = pos[b] - pos[a];
      glm::dvec3 side = glm::cross(e, n);
      const double sl = glm::length(side);
      if (!(sl > 0)) continue;
      side /= sl;
      const Quadric edge = Quadric::plane(side, -glm::dot(side, pos[a]), glm::length(e));
      q[a] += edge, q[b] += edge;
    }
  }
  std::vector<uint8_t> cls(nv);
  for (size_t v = 0; v < nv; ++v)
    cls[v] = boundaryEdges[v] == 0 ? kFree : boundaryEdges[v] == 2 ? kBoundaryLine : kFixed;
  st.setup += since(clock);

  struct Candidate {
    float key;
    uint32_t gone, stays;
    glm::dvec3 place;
  };
  std::vector<Candidate> cands;
  std::vector<uint64_t> order;
  std::vector<uint8_t> locked(nv);
  std::vector<uint32_t> stamp(nv, 0);
  uint32_t stampNow = 0;
  const double cos = std::cos(opt.maxNormalDeviationDeg * std::numbers::pi / 180.0);
  const double cos2 = cos * cos, minQ2 = opt.minTriangleQuality * opt.minTriangleQuality;
  size_t live = nf;
  bool first = true;
  while (live > targetTriangles) {
    ++st.passes;
    if (!first) lists.build(fv, dead, nv);
    first = false;
    st.lists += since(clock);

    // Every edge once: interior edges from the face where they run a->b
    // with a < b, boundary edges from their one face.
    cands.clear();
    auto liveFacesWith = [&](uint32_t a, uint32_t b) {
      int n = 0;
      for (uint32_t i = lists.offset[a]; i < lists.offset[a + 1]; ++i) n += hasVertex(&fv[size_t(lists.face[i]) * 3], b);
      return n;
    };
    for (size_t f = 0; f < nf; ++f) {
      if (dead[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = fv[f * 3 + k], b = fv[f * 3 + (k + 1) % 3];
        const bool boundary = (cls[a] != kFree || cls[b] != kFree) && liveFacesWith(a, b) == 1;
        if (!boundary && a > b) continue;
        ++st.evaluations;
        const glm::dvec3 t = pos[b] - pos[a];
        const double len2 = glm::dot(t, t);
        const Quadric qq = q[a] + q[b];
        const double inv = qq.weight > 0 ? 1.0 / qq.weight : 0.0;
        if (cls[a] == kFree && cls[b] == kFree && !opt.endpointPlacement) {
          glm::dvec3 p;
          const double cost = placeOnEdge(qq, pos[a], pos[b], p);
          cands.push_back({float(cost * inv + opt.lengthWeight * len2), a, b, p});
          continue;
        }
        // A free vertex goes only along interior edges, a boundary-line
        // vertex only along its boundary; it lands on the other end.
        const bool aGoes = cls[a] == kFree ? !boundary : cls[a] == kBoundaryLine && boundary;
        const bool bGoes = cls[b] == kFree ? !boundary : cls[b] == kBoundaryLine && boundary;
        const double ea = aGoes ? qq.evaluate(pos[b]) * inv : HUGE_VAL;
        const double eb = bGoes ? qq.evaluate(pos[a]) * inv : HUGE_VAL;
        if (!(std::min(ea, eb) < HUGE_VAL)) continue;
        if (ea <= eb)
          cands.push_back({float(ea + opt.lengthWeight * len2), a, b, pos[b]});
        else
          cands.push_back({float(eb + opt.lengthWeight * len2), b, a, pos[a]});
      }
    }
    st.evaluate += since(clock);

    order.resize(cands.size());
    for (size_t i = 0; i < cands.size(); ++i) {
      uint32_t bits;
      const float k = cands[i].key > 0 ? cands[i].key : 0.0f;
      std::memcpy(&bits, &k, 4);
      order[i] = (uint64_t(bits) << 32) | i;
    }
    hs::mesh::radixSortByKey(std::span<uint64_t>(order), 32, 1);
    st.sort += since(clock);

    const size_t facesToGo = live - targetTriangles, goal = facesToGo / 2;
    const float limit = goal < order.size() ? float(opt.passLimit) * cands[uint32_t(order[goal])].key : HUGE_VALF;
    std::fill(locked.begin(), locked.end(), 0);
    size_t removed = 0, passCollapses = 0;
    for (const uint64_t o : order) {
      const Candidate& c = cands[uint32_t(o)];
      ++st.walked;
      if (locked[c.gone] || locked[c.stays]) continue;
      if (removed >= facesToGo || (c.key > limit && removed > facesToGo / 10)) break;
      ++st.tried;
      const uint32_t v0 = c.gone, v1 = c.stays;
      const glm::dvec3 p = c.place;
      // Link condition: the only common neighbours of v0 and v1 are the
      // third corners of the faces on the edge (one or two of them).
      ++stampNow;
      int onEdge = 0;
      uint32_t opposite[2] = {UINT32_MAX, UINT32_MAX};
      for (uint32_t i = lists.offset[v0]; i < lists.offset[v0 + 1]; ++i) {
        const uint32_t f = lists.face[i];
        if (dead[f]) continue;
        const uint32_t* t = &fv[size_t(f) * 3];
        stamp[t[0]] = stamp[t[1]] = stamp[t[2]] = stampNow;
        if (hasVertex(t, v1)) {
          if (onEdge < 2) opposite[onEdge] = t[0] != v0 && t[0] != v1 ? t[0] : t[1] != v0 && t[1] != v1 ? t[1] : t[2];
          ++onEdge;
        }
      }
      bool ok = onEdge == 1 || onEdge == 2;
      for (uint32_t i = lists.offset[v1]; ok && i < lists.offset[v1 + 1]; ++i) {
        const uint32_t f = lists.face[i];
        if (dead[f]) continue;
        for (const uint32_t x : {fv[size_t(f) * 3], fv[size_t(f) * 3 + 1], fv[size_t(f) * 3 + 2]})
          if (x != v0 && x != v1 && x != opposite[0] && x != opposite[1] && stamp[x] == stampNow) ok = false;
      }
      if (ok && onEdge == 2 && cls[v0] != kFree && cls[v1] != kFree) ok = false;  // would pinch the surface
      if (!ok) {
        ++st.rejectedTopology;
        continue;
      }
      // The faces that stay, at the new place: none turns by more than the
      // allowed angle or becomes a sliver (CollapseEngine::geometryOk's
      // tests, squared instead of through square roots).
      auto faceOk = [&](const uint32_t* t, uint32_t moved) {
        glm::dvec3 a[3], b[3];
        for (int k = 0; k < 3; ++k) a[k] = pos[t[k]], b[k] = t[k] == moved ? p : a[k];
        const glm::dvec3 n0 = glm::cross(a[1] - a[0], a[2] - a[0]), n1 = glm::cross(b[1] - b[0], b[2] - b[0]);
        const double l0 = glm::dot(n0, n0), l1 = glm::dot(n1, n1), d = glm::dot(n0, n1);
        if (!(l1 > 0)) return false;
        if (l0 > 0 && (d < 0 || d * d < cos2 * l0 * l1)) return false;
        const double e = glm::dot(b[1] - b[0], b[1] - b[0]) + glm::dot(b[2] - b[1], b[2] - b[1]) +
                         glm::dot(b[0] - b[2], b[0] - b[2]);
        return 12.0 * l1 >= minQ2 * e * e;  // 4 sqrt(3) area / e >= minQ, with area = |n1| / 2
      };
      for (const uint32_t v : {v0, v1}) {
        if (v == v1 && p == pos[v1]) break;  // the kept vertex stays: its faces do not change
        for (uint32_t i = lists.offset[v]; ok && i < lists.offset[v + 1]; ++i) {
          const uint32_t f = lists.face[i];
          const uint32_t* t = &fv[size_t(f) * 3];
          if (!dead[f] && !(hasVertex(t, v0) && hasVertex(t, v1)) && !faceOk(t, v)) ok = false;
        }
      }
      if (!ok) {
        ++st.rejectedGeometry;
        continue;
      }
      // v0's faces move to v1 (its own list is not extended: v1 is locked
      // until the lists are rebuilt), the two on the edge die.
      for (uint32_t i = lists.offset[v0]; i < lists.offset[v0 + 1]; ++i) {
        const uint32_t f = lists.face[i];
        if (dead[f]) continue;
        uint32_t* t = &fv[size_t(f) * 3];
        if (hasVertex(t, v1)) {
          dead[f] = 1, --live, ++removed;
          continue;
        }
        for (int k = 0; k < 3; ++k)
          if (t[k] == v0) t[k] = v1;
      }
      pos[v1] = p;
      q[v1] += q[v0];
      locked[v0] = locked[v1] = 1;
      if (opt.lockOneRings)
        for (const uint32_t v : {v0, v1})
          for (uint32_t i = lists.offset[v]; i < lists.offset[v + 1]; ++i)
            if (!dead[lists.face[i]])
              for (int k = 0; k < 3; ++k) locked[fv[size_t(lists.face[i]) * 3 + k]] = 1;
      ++st.collapses, ++passCollapses;
    }
    st.collapse += since(clock);
    if (passCollapses == 0) break;  // nothing left that passes the checks
  }

  hs::mesh::MeshData out;
  out.origin = in.origin;
  std::vector<uint32_t> id(nv, UINT32_MAX);
  for (size_t f = 0; f < nf; ++f) {
    if (dead[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = fv[f * 3 + k];
      if (id[v] == UINT32_MAX) id[v] = uint32_t(out.positions.size()), out.positions.push_back(glm::vec3(pos[v] + center));
      out.indices.push_back(id[v]);
    }
  }
  out.submeshes.push_back({0, uint32_t(out.indices.size()), -1});
  return out;
}

}  // namespace hs::bench
