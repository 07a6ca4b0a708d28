#include "meshproc/error_metrics.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "core/parallel.h"
#include "mesh/nonmanifold_split.h"
#include "mesh/weld.h"
#include "meshproc/surface_sampling.h"

namespace hs::mesh {
namespace {

glm::dvec3 corner(const MeshData& m, size_t f, size_t k) { return glm::dvec3(m.positions[m.indices[f * 3 + k]]); }

struct Polylines {
  std::vector<uint8_t> constrainedPos;  // per welded position
  std::vector<uint32_t> posOf;          // per vertex
  uint32_t positions = 0;
  MeshData segments;                    // each constrained edge as a zero-area triangle (a, b, b)
  NonManifoldCounts nonManifold;
};

// Boundary edges, seams (the faces on either side use different UVs or
// materials) and non-manifold edges, found on the position-welded topology.
// `reference`: also the edges between a face and its own reversed copy.
// Such a pair is one two-sided face, glued to itself along its border
// edges; once the cleaning or the decimation parts the copy from it (or
// lets it go), those edges are the surface's border, and the result's
// vertices on them stand where the input's were. Only the original's
// polylines, the reference a result is checked against, count them: a
// result's vertex is checked if the result has it on a border.
Polylines findPolylines(const MeshData& m, unsigned threads, bool reference) {
  Polylines pl;
  pl.posOf = weldMap(m.positions, {}, {}, pl.positions);
  uint32_t nWedge = 0;
  const bool hasUv = m.uvs.size() == m.positions.size() && !m.uvs.empty();
  const std::vector<uint32_t> wedgeOf = hasUv ? weldMap(m.positions, m.uvs, {}, nWedge) : pl.posOf;
  const size_t nf = m.triangleCount();
  std::vector<uint32_t> tris(nf * 3);
  for (size_t c = 0; c < tris.size(); ++c) tris[c] = pl.posOf[m.indices[c]];
  const CornerTopology topo = analyzeCorners(tris, pl.positions, threads);
  pl.nonManifold = {topo.nonManifoldEdges, topo.nonManifoldVertices};
  const std::vector<int> mat = faceMaterials(m);
  pl.constrainedPos.assign(pl.positions, 0);
  pl.segments.origin = m.origin;
  for (uint32_t c = 0; c < tris.size(); ++c) {
    const uint32_t a = tris[c], b = tris[nextCorner(c)];
    if (a == b || a == tris[nextCorner(nextCorner(c))] || b == tris[nextCorner(nextCorner(c))]) continue;
    const uint32_t t = topo.twin[c];
    bool constrained = t == kNoCorner;
    if (!constrained) {
      if (t < c) continue;  // seen from the twin
      const bool ownReversedCopy = tris[nextCorner(nextCorner(c))] == tris[nextCorner(nextCorner(t))];
      constrained = (reference && ownReversedCopy) || mat[c / 3] != mat[t / 3] ||
                    wedgeOf[m.indices[c]] != wedgeOf[m.indices[nextCorner(t)]] ||
                    wedgeOf[m.indices[nextCorner(c)]] != wedgeOf[m.indices[t]];
    }
    if (!constrained) continue;
    pl.constrainedPos[a] = pl.constrainedPos[b] = 1;
    const uint32_t base = uint32_t(pl.segments.positions.size());
    pl.segments.positions.push_back(m.positions[m.indices[c]]);
    pl.segments.positions.push_back(m.positions[m.indices[nextCorner(c)]]);
    pl.segments.indices.insert(pl.segments.indices.end(), {base, base + 1, base + 1});
  }
  return pl;
}

double area(const MeshData& m) {
  double a = 0;
  for (size_t f = 0; f < m.triangleCount(); ++f) a += 0.5 * faceDoubleArea(m, f);
  return a;
}

// Signed volume by the divergence theorem, relative to `ref` in m's frame.
double signedVolume(const MeshData& m, const glm::dvec3& ref) {
  double v = 0;
  for (size_t f = 0; f < m.triangleCount(); ++f)
    v += glm::dot(corner(m, f, 0) - ref, glm::cross(corner(m, f, 1) - ref, corner(m, f, 2) - ref));
  return v / 6.0;
}

// The largest distance from `from`'s vertices (shifted by `offset`) to
// `target`'s surface: the vertices' part of a direction's maximum.
double vertexDistanceMax(const MeshData& from, const ClosestPointBvh& target, const glm::dvec3& offset,
                         unsigned threads) {
  std::vector<double> maxOf(std::max(1u, threads), 0.0);
  parallelRanges(from.vertexCount(), threads, [&](size_t b, size_t e, unsigned w) {
    uint32_t hint = UINT32_MAX;
    double mx = 0;
    for (size_t v = b; v < e; ++v) {
      const auto hit = target.closest(glm::dvec3(from.positions[v]) + offset, hint);
      hint = hit.face;
      mx = std::max(mx, std::sqrt(hit.distanceSq));
    }
    maxOf[w] = std::max(maxOf[w], mx);
  });
  double m = 0;
  for (double x : maxOf) m = std::max(m, x);
  return m;
}

// A bound from above on the largest distance from `from`'s surface to
// `target`'s (offset: `from`'s frame -> the target's). For a point p of a
// piece of a face, and any triangle T of the target, dist(p, target) <=
// dist(p, T), and dist(., T) is convex (T is convex), so over the piece it
// is largest at a corner: the piece's bound is the least, over the
// triangles nearest its corners, of the largest corner distance to that
// triangle; and through two of them, parted by a plane (pairBound). A
// piece whose bound is above `threshold` (1 + `slack`) is cut
// into four (edge midpoints) down to `maxDepth`; one at or below the
// threshold cannot hold a point further than it, and one within the slack
// above it keeps its bound. Returns the largest bound left above the
// threshold (0 when none), and counts the pieces examined.
double distanceUpperBound(const MeshData& from, const MeshData& target, const ClosestPointBvh& bvh,
                          const glm::dvec3& offset, double threshold, double slack, int maxDepth, unsigned threads,
                          uint64_t& pieces) {
  const size_t nf = from.triangleCount();
  std::vector<double> maxOf(std::max(1u, threads), 0.0);
  std::vector<uint64_t> countOf(std::max(1u, threads), 0);
  const double t2 = threshold * threshold, slack2 = t2 * (1.0 + slack) * (1.0 + slack);
  parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned w) {
    struct Piece {
      glm::dvec3 p[3];
      uint32_t near[3];
      int depth;
    };
    std::vector<Piece> stack;
    uint32_t hint = UINT32_MAX;
    auto nearest = [&](const glm::dvec3& q) {
      const auto hit = bvh.closest(q, hint);
      hint = hit.face;
      return hit.face;
    };
    auto distSq = [&](const glm::dvec3& q, uint32_t t) {
      glm::dvec3 cp, bary;
      return closestPointOnTriangle(q, corner(target, t, 0), corner(target, t, 1), corner(target, t, 2), cp, bary);
    };
    // The bound of a triangular piece through triangles ta and tb (squared),
    // giving up once it cannot beat `best`.
    auto pairBound = [&](const glm::dvec3 (&p)[3], uint32_t ta, uint32_t tb, double best) {
      glm::dvec3 va[3], vb[3];
      for (int k = 0; k < 3; ++k) va[k] = corner(target, ta, size_t(k)), vb[k] = corner(target, tb, size_t(k));
      // Their shared edge (by position), if any.
      int shared[2], n = 0;
      for (int k = 0; k < 3 && n < 2; ++k)
        for (int l = 0; l < 3; ++l)
          if (va[k] == vb[l]) {
            shared[n++] = k;
            break;
          }
      const glm::dvec3 ca = (va[0] + va[1] + va[2]) / 3.0, cb = (vb[0] + vb[1] + vb[2]) / 3.0;
      glm::dvec3 normal, origin;
      if (n == 2) {
        const glm::dvec3 edge = va[shared[1]] - va[shared[0]];
        const glm::dvec3 na = glm::normalize(glm::cross(va[1] - va[0], va[2] - va[0]));
        const glm::dvec3 nb = glm::normalize(glm::cross(vb[1] - vb[0], vb[2] - vb[0]));
        normal = glm::cross(edge, na + nb);
        origin = va[shared[0]];
      } else {
        normal = cb - ca;  // the plane halfway between their centres
        origin = 0.5 * (ca + cb);
      }
      if (!(glm::dot(normal, normal) > 0) || !std::isfinite(glm::dot(normal, normal))) return HUGE_VAL;
      const bool aPositive = glm::dot(ca - origin, normal) >= 0;
      double side[3];
      for (int k = 0; k < 3; ++k) side[k] = glm::dot(p[k] - origin, normal);
      double worst = 0;
      auto consider = [&](const glm::dvec3& q, bool positive) {
        worst = std::max(worst, distSq(q, positive == aPositive ? ta : tb));
      };
      for (int k = 0; k < 3 && worst < best; ++k) {
        consider(p[k], side[k] >= 0);
        const int l = (k + 1) % 3;
        if ((side[k] < 0) != (side[l] < 0)) {  // the edge crosses the plane: the point is on both pieces
          const double t = side[k] / (side[k] - side[l]);
          const glm::dvec3 q = p[k] + t * (p[l] - p[k]);
          consider(q, true);
          consider(q, false);
        }
      }
      return worst;
    };
    double mx = 0;
    uint64_t count = 0;
    for (size_t f = b; f < e; ++f) {
      Piece root;
      for (int k = 0; k < 3; ++k) root.p[k] = corner(from, f, size_t(k)) + offset, root.near[k] = nearest(root.p[k]);
      root.depth = 0;
      stack.push_back(root);
      while (!stack.empty()) {
        const Piece pc = stack.back();
        stack.pop_back();
        ++count;
        double bound = HUGE_VAL;
        for (int i = 0; i < 3 && bound > t2; ++i) {
          const bool seen = (i >= 1 && pc.near[i] == pc.near[0]) || (i == 2 && pc.near[2] == pc.near[1]);
          if (seen) continue;
          double worst = 0;
          for (int k = 0; k < 3 && worst < bound; ++k) worst = std::max(worst, distSq(pc.p[k], pc.near[i]));
          bound = std::min(bound, worst);
        }
        // Two triangles: any plane parts the piece into two convex pieces,
        // each bounded through one of them at its corners (the piece's
        // corners on that side and where its edges cross the plane). The
        // plane through their shared edge, halfway between their normals,
        // makes the bound tight for a piece lying over both.
        for (int i = 0; i < 3 && bound > slack2; ++i)
          for (int j = i + 1; j < 3 && bound > slack2; ++j) {
            const uint32_t ta = pc.near[i], tb = pc.near[j];
            if (ta == tb) continue;
            const double pair = pairBound(pc.p, ta, tb, bound);
            bound = std::min(bound, pair);
          }
        if (bound <= t2) continue;
        if (pc.depth >= maxDepth || bound <= slack2) {
          mx = std::max(mx, std::sqrt(bound));
          continue;
        }
        const glm::dvec3 m01 = 0.5 * (pc.p[0] + pc.p[1]), m12 = 0.5 * (pc.p[1] + pc.p[2]),
                         m20 = 0.5 * (pc.p[2] + pc.p[0]);
        const uint32_t n01 = nearest(m01), n12 = nearest(m12), n20 = nearest(m20);
        const int d = pc.depth + 1;
        stack.push_back({{pc.p[0], m01, m20}, {pc.near[0], n01, n20}, d});
        stack.push_back({{m01, pc.p[1], m12}, {n01, pc.near[1], n12}, d});
        stack.push_back({{m20, m12, pc.p[2]}, {n20, n12, pc.near[2]}, d});
        stack.push_back({{m01, m12, m20}, {n01, n12, n20}, d});
      }
    }
    maxOf[w] = std::max(maxOf[w], mx);
    countOf[w] += count;
  }, 64);
  double m = 0;
  for (double x : maxOf) m = std::max(m, x);
  for (uint64_t c : countOf) pieces += c;
  return m;
}

// Distances from `total` seeded samples on `from` to the surface in
// `target` (its vertices are vertexDistanceMax's). `offset` takes `from`'s
// local coordinates into the target's. Face samples land in `out`, their
// largest in `maxDist`.
bool sampleDistances(const MeshData& from, const std::vector<uint64_t>& first, uint64_t seed,
                     const ClosestPointBvh& target, const glm::dvec3& offset, float* out, double& maxDist,
                     unsigned threads, const Progress* progress) {
  const size_t nf = from.triangleCount();
  std::vector<double> maxOf(std::max(1u, threads), 0.0);
  std::atomic<bool> stop{false};
  parallelRanges(nf, threads, [&](size_t b, size_t e, unsigned w) {
    uint32_t hint = UINT32_MAX;
    double mx = 0;
    // One face's samples are looked up together (closestMany).
    std::vector<glm::dvec3> points;
    std::vector<ClosestPointBvh::Hit> hits;
    ClosestPointBvh::ManyScratch scratch;
    for (size_t f = b; f < e && !stop; ++f) {
      if ((f & 4095) == 0 && isCancelled(progress)) stop = true;
      const uint64_t count = first[f + 1] - first[f];
      if (count == 0) continue;
      points.resize(count);
      hits.resize(count);
      faceSamples(from, f, seed, offset, points);
      hint = target.closestMany(points, hint, hits, scratch);
      for (uint64_t k = 0; k < count; ++k) {
        const double d = std::sqrt(hits[k].distanceSq);
        out[first[f] + k] = float(d);
        mx = std::max(mx, d);
      }
    }
    maxOf[w] = std::max(maxOf[w], mx);
  }, 256);
  for (double m : maxOf) maxDist = std::max(maxDist, m);
  return !stop;
}

// Mean, RMS and 95th percentile of d[0..n) (reorders d).
void summarize(float* d, uint64_t n, DistanceStats& s) {
  s.samples = n;
  if (n == 0) return;
  double sum = 0, sumSq = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const double v = double(d[i]);
    sum += v, sumSq += v * v;
  }
  s.mean = sum / double(n);
  s.rms = std::sqrt(sumSq / double(n));
  const uint64_t k = std::min<uint64_t>(n - 1, uint64_t(std::ceil(0.95 * double(n))) - 1);
  std::nth_element(d, d + k, d + n);
  s.p95 = d[k];
}

}  // namespace

NonManifoldCounts countNonManifold(const MeshData& mesh, unsigned threads) {
  uint32_t n = 0;
  const std::vector<uint32_t> posOf = weldMap(mesh.positions, {}, {}, n);
  std::vector<uint32_t> tris(mesh.indices.size());
  for (size_t c = 0; c < tris.size(); ++c) tris[c] = mesh.indices[c] < posOf.size() ? posOf[mesh.indices[c]] : UINT32_MAX;
  const CornerTopology t = analyzeCorners(tris, n, resolveThreads(threads));
  return {t.nonManifoldEdges, t.nonManifoldVertices};
}

struct ErrorMeter::Original {
  const MeshData& mesh;
  ErrorOptions opt;
  unsigned threads = 1;
  ClosestPointBvh bvh;
  Polylines polylines;
  ClosestPointBvh polylineBvh;
  std::vector<int> material;
  double diagonal = 0, area = 0, volume = 0;
  glm::dvec3 volumeRef{0.0};
  uint64_t total = 0;
  std::vector<uint64_t> first;
  Original(const MeshData& m, const ErrorOptions& o) : mesh(m), opt(o) {}
};

const MeshData& ErrorMeter::original() const { return o_->mesh; }
const ClosestPointBvh& ErrorMeter::originalBvh() const { return o_->bvh; }

ErrorMeter::Facing ErrorMeter::facing(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                      uint32_t hintFace) const {
  Facing r;
  const glm::dvec3 n = glm::cross(b - a, c - a);
  if (!(glm::dot(n, n) > 0)) return r;
  r.hit = o_->bvh.closest((a + b + c) / 3.0, hintFace);
  if (!r.hit.found()) return r;
  const MeshData& orig = o_->mesh;
  const glm::dvec3 on = glm::cross(corner(orig, r.hit.face, 1) - corner(orig, r.hit.face, 0),
                                   corner(orig, r.hit.face, 2) - corner(orig, r.hit.face, 0));
  r.checked = true;
  r.against = glm::dot(n, on) < 0;
  return r;
}

ErrorMeter::ErrorMeter(const MeshData& original, const ErrorOptions& options)
    : o_(std::make_unique<Original>(original, options)) {
  Original& o = *o_;
  o.threads = resolveThreads(options.threads);
  o.bvh = ClosestPointBvh(original, o.threads);
  o.polylines = findPolylines(original, o.threads, true);
  if (!o.polylines.segments.indices.empty()) o.polylineBvh = ClosestPointBvh(o.polylines.segments, o.threads);
  o.material = faceMaterials(original);
  const Bounds b = original.bounds();
  o.diagonal = b.empty ? 0.0 : glm::length(glm::dvec3(b.max) - glm::dvec3(b.min));
  o.volumeRef = b.empty ? glm::dvec3(0.0) : (glm::dvec3(b.min) + glm::dvec3(b.max)) * 0.5;
  o.area = area(original);
  o.volume = signedVolume(original, o.volumeRef);
  const double wanted = std::max(0.0, options.samplesPerFace) * double(original.triangleCount());
  o.total = std::min<uint64_t>(options.maxSamples, uint64_t(std::llround(wanted)));
  o.first = allocateSamples(original, o.total);
}

ErrorMeter::~ErrorMeter() = default;

ErrorMeter::VertexCheck ErrorMeter::checkVertices(const MeshData& s) const {
  const Original& o = *o_;
  const glm::dvec3 toOrig = s.origin - o.mesh.origin;
  VertexCheck v;
  v.bvh = ClosestPointBvh(s, o.threads);
  v.forward = vertexDistanceMax(o.mesh, v.bvh, -toOrig, o.threads);
  v.backward = vertexDistanceMax(s, o.bvh, toOrig, o.threads);
  return v;
}

HausdorffBound ErrorMeter::hausdorffUpperBound(const MeshData& s, double lowerBound, double slack, int maxDepth,
                                               const VertexCheck* check) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Original& o = *o_;
  const glm::dvec3 toOrig = s.origin - o.mesh.origin;
  const ClosestPointBvh own = check ? ClosestPointBvh() : ClosestPointBvh(s, o.threads);
  const ClosestPointBvh& sBvh = check ? check->bvh : own;
  HausdorffBound h;
  h.lower = lowerBound;
  const double fwd = distanceUpperBound(o.mesh, s, sBvh, -toOrig, lowerBound, slack, maxDepth, o.threads, h.pieces);
  const double bwd = distanceUpperBound(s, o.mesh, o.bvh, toOrig, lowerBound, slack, maxDepth, o.threads, h.pieces);
  h.upper = std::max({lowerBound, fwd, bwd});
  h.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return h;
}

ErrorReport ErrorMeter::measure(const MeshData& s, const Progress* progress, const VertexCheck* check) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Original& o = *o_;
  const MeshData& orig = o.mesh;
  ErrorReport r;
  r.seed = o.opt.seed;
  r.bboxDiagonal = o.diagonal;
  r.samplesPerFace = orig.triangleCount() ? double(o.total) / double(orig.triangleCount()) : 0.0;
  r.areaIn = o.area;
  r.volumeIn = o.volume;
  r.nonManifoldIn = o.polylines.nonManifold;
  // s's local coordinates -> the original's frame, in double.
  const glm::dvec3 toOrig = s.origin - orig.origin;
  r.areaOut = area(s);
  r.volumeOut = signedVolume(s, o.volumeRef - toOrig);

  const VertexCheck own = check ? VertexCheck{} : checkVertices(s);
  const VertexCheck& atVertices = check ? *check : own;
  const ClosestPointBvh& sBvh = atVertices.bvh;
  const std::vector<uint64_t> sFirst = allocateSamples(s, o.total);
  const uint64_t nFwd = o.first.back(), nBwd = sFirst.back();
  std::vector<float> d(nFwd + nBwd);
  reportProgress(progress, 0.1, "Measuring error (original to result)");
  // Each direction's maximum: its samples' and its vertices'.
  double fwdMax = atVertices.forward, bwdMax = atVertices.backward;
  bool ok = sampleDistances(orig, o.first, o.opt.seed, sBvh, -toOrig, d.data(), fwdMax, o.threads, progress);
  reportProgress(progress, 0.5, "Measuring error (result to original)");
  ok = ok && sampleDistances(s, sFirst, o.opt.seed + 1, o.bvh, toOrig, d.data() + nFwd, bwdMax, o.threads, progress);
  if (!ok) {
    r.cancelled = true;
    return r;
  }
  // Symmetric mean and RMS before the percentile passes reorder the array.
  summarize(d.data(), nFwd, r.forward);
  summarize(d.data() + nFwd, nBwd, r.backward);
  r.forward.max = fwdMax;
  r.backward.max = bwdMax;
  DistanceStats both;
  summarize(d.data(), nFwd + nBwd, both);
  r.hausdorff = std::max(fwdMax, bwdMax);
  r.mean = both.mean, r.rms = both.rms, r.p95 = both.p95;
  d = {};

  // Per simplified face, at its centre: orientation against the original
  // surface there, and where the texture lands.
  reportProgress(progress, 0.85, "Checking normals and texture coordinates");
  const size_t nf = s.triangleCount();
  const std::vector<int> sMat = faceMaterials(s);
  const bool uvBoth = !s.uvs.empty() && s.uvs.size() == s.positions.size() && !orig.uvs.empty() &&
                      orig.uvs.size() == orig.positions.size();
  auto texSize = [&](int material) -> glm::ivec2 {
    if (o.opt.textureWidth > 0 && o.opt.textureHeight > 0) return {o.opt.textureWidth, o.opt.textureHeight};
    if (material < 0 || size_t(material) >= s.materials.size()) return {0, 0};
    const int t = s.materials[size_t(material)].diffuseTexture;
    const auto& texSrc = size_t(t) < s.textures.size() ? s.textures : orig.textures;
    if (t < 0 || size_t(t) >= texSrc.size()) return {0, 0};
    return {texSrc[size_t(t)].width, texSrc[size_t(t)].height};
  };
  std::vector<uint8_t> flipped(nf, 0), checked(nf, 0);
  std::vector<float> uvDisp(uvBoth ? nf : 0, -1.0f);
  parallelRanges(nf, o.threads, [&](size_t b, size_t e, unsigned) {
    uint32_t hint = UINT32_MAX;
    for (size_t f = b; f < e; ++f) {
      const Facing facingF = facing(corner(s, f, 0) + toOrig, corner(s, f, 1) + toOrig, corner(s, f, 2) + toOrig, hint);
      if (!facingF.checked) continue;
      const auto& hit = facingF.hit;
      hint = hit.face;
      checked[f] = 1;
      flipped[f] = facingF.against;
      if (uvBoth && sMat[f] == o.material[hit.face]) {
        const glm::ivec2 size = texSize(sMat[f]);
        if (size.x > 0 && size.y > 0) {
          const glm::dvec2 uvS = (glm::dvec2(s.uvs[s.indices[f * 3]]) + glm::dvec2(s.uvs[s.indices[f * 3 + 1]]) +
                                  glm::dvec2(s.uvs[s.indices[f * 3 + 2]])) / 3.0;
          const glm::dvec2 uvO = hit.bary.x * glm::dvec2(orig.uvs[orig.indices[hit.face * 3]]) +
                                 hit.bary.y * glm::dvec2(orig.uvs[orig.indices[hit.face * 3 + 1]]) +
                                 hit.bary.z * glm::dvec2(orig.uvs[orig.indices[hit.face * 3 + 2]]);
          uvDisp[f] = float(glm::length((uvS - uvO) * glm::dvec2(size)));
        }
      }
    }
  }, 256);
  for (size_t f = 0; f < nf; ++f) r.facesChecked += checked[f], r.flippedNormals += flipped[f];
  std::vector<float> uv;
  for (float v : uvDisp)
    if (v >= 0) uv.push_back(v);
  if (!uv.empty()) {
    DistanceStats us;
    us.max = *std::max_element(uv.begin(), uv.end());
    summarize(uv.data(), uv.size(), us);
    r.uvMeasured = true;
    r.uvMaxTexels = us.max, r.uvMeanTexels = us.mean, r.uvP95Texels = us.p95, r.uvSamples = uv.size();
    const glm::ivec2 size = texSize(s.submeshes.empty() ? -1 : s.submeshes[0].material);
    r.textureWidth = size.x, r.textureHeight = size.y;
  }

  // Boundary and seam vertices of the result against the original polylines.
  const Polylines sp = findPolylines(s, o.threads, false);
  r.nonManifoldOut = sp.nonManifold;
  std::vector<uint8_t> seen(sp.positions, 0);
  const double tol = 1e-6 * o.diagonal;
  for (size_t v = 0; v < s.vertexCount(); ++v) {
    const uint32_t p = sp.posOf[v];
    if (!sp.constrainedPos[p] || seen[p]) continue;
    seen[p] = 1;
    ++r.constrainedVerticesOut;
    const glm::dvec3 q = glm::dvec3(s.positions[v]) + toOrig;
    const double dist = o.polylineBvh.empty() ? HUGE_VAL : std::sqrt(o.polylineBvh.closest(q).distanceSq);
    if (dist > tol) {
      ++r.constrainedVerticesMoved;
      if (std::isfinite(dist)) r.constrainedMaxDeviation = std::max(r.constrainedMaxDeviation, dist);
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (o.opt.certify && !isCancelled(progress)) {
    reportProgress(progress, 0.95, "Certifying the maximum");
    const HausdorffBound b = hausdorffUpperBound(s, r.hausdorff, 0.01, 10, &atVertices);
    r.certified = true;
    r.hausdorffUpper = std::max(b.upper, r.hausdorff);
    r.certifiedPieces = b.pieces;
    r.certifySeconds = b.seconds;
  }
  reportProgress(progress, 1.0, "Error measured");
  return r;
}

ErrorReport measureError(const MeshData& original, const MeshData& simplified, const ErrorOptions& options,
                         const Progress* progress) {
  return ErrorMeter(original, options).measure(simplified, progress);
}

}  // namespace hs::mesh
