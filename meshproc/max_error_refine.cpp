#include "meshproc/max_error_refine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "meshproc/closest_point_bvh.h"
#include "meshproc/decimate_trace.h"
#include "meshproc/error_metrics.h"
#include "meshproc/float_store.h"
#include "meshproc/minimax_move.h"

namespace hs::mesh {
namespace {

using minimax::Constraint;
using minimax::minimaxMove;
using minimax::towardsLeastSquares;
using minimax::worst;

uint64_t positionKey(const glm::vec3& p) {
  const glm::vec3 q = p + glm::vec3(0.0f);  // -0 and +0 compare equal: one key
  uint32_t b[3];
  std::memcpy(b, &q, sizeof b);
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint32_t x : b) h = (h ^ x) * 0xBF58476D1CE4E5B9ull, h ^= h >> 31;
  return h;
}

}  // namespace

RefineReport refineMaxError(const ErrorMeter& meter, MeshData& result, const RefineOptions& opt,
                            const Progress* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  DecimateTrace trace;
  RefineReport rep;
  auto finish = [&] {
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
  };
  const MeshData& original = meter.original();
  const ClosestPointBvh& originalBvh = meter.originalBvh();
  const size_t nv = result.positions.size(), nf = result.triangleCount(), no = original.positions.size();
  if (nf == 0 || no == 0 || originalBvh.empty() || opt.iterations <= 0) return finish();
  const unsigned threads = resolveThreads(opt.threads);
  // Result frame -> original frame: add `shift`.
  const glm::dvec3 shift = result.origin - original.origin;
  const std::vector<uint32_t>& idx = result.indices;
  reportProgress(progress, 0.0, "Refining vertices");

  // Faces around each vertex (in face order), and each face's material.
  std::vector<uint32_t> fanStart(nv + 1, 0), fan(nf * 3);
  for (uint32_t v : idx) ++fanStart[v + 1];
  for (size_t v = 0; v < nv; ++v) fanStart[v + 1] += fanStart[v];
  {
    std::vector<uint32_t> fill(fanStart.begin(), fanStart.end() - 1);
    for (size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) fan[fill[idx[f * 3 + k]]++] = uint32_t(f);
  }
  const std::vector<int> material = faceMaterials(result);

  // Screening: each original vertex's nearest result face and distance,
  // and each result face's largest distance to the original at a coarse
  // grid (corners and edge midpoints).
  trace.mark("refine: fans");
  const ClosestPointBvh resultBvh(result, threads);
  trace.mark("refine: result bvh");
  std::vector<uint32_t> nearFace(no);
  std::vector<float> nearDist(no);
  parallelFor(int64_t(no), int(threads), 1024, [&](int64_t b, int64_t e) {
    uint32_t hint = UINT32_MAX;
    for (int64_t i = b; i < e; ++i) {
      const auto h = resultBvh.closest(glm::dvec3(original.positions[size_t(i)]) - shift, hint);
      nearFace[size_t(i)] = h.face, nearDist[size_t(i)] = float(std::sqrt(h.distanceSq)), hint = h.face;
    }
  });
  if (isCancelled(progress)) return rep.cancelled = true, finish();
  trace.mark("refine: original->result");
  // Result -> original, only the distances that can make a candidate need
  // to be exact: those from `candidateShare` of the largest so far (the
  // original's vertices') up. Below that a query stops at the first
  // triangle that near (an upper bound, still below it): the candidates
  // and the largest distance are the same. Only the largest distance away
  // from the candidates, below that share, can come out higher, and it
  // steers the rounds only once they have halved the largest (never seen:
  // the same moves on every mesh of docs/meshes.md's table).
  const float fromOriginal = no ? *std::max_element(nearDist.begin(), nearDist.end()) : 0.0f;
  const double exactFrom = opt.candidateShare * double(fromOriginal);
  const double stopSq = exactFrom * exactFrom * (1.0 - 1e-6);
  // Each vertex once, and each edge's midpoint once: from the face that
  // runs it from the lower vertex number to the higher (the other face of
  // a consistently oriented edge runs it the other way; a border edge run
  // the other way is left to its corners).
  std::vector<float> vertexDist(nv, 0.0f), faceWorst(nf, 0.0f);
  parallelFor(int64_t(nv), int(threads), 1024, [&](int64_t b, int64_t e) {
    uint32_t hint = UINT32_MAX;
    for (int64_t v = b; v < e; ++v) {
      const auto h = originalBvh.closestUnless(glm::dvec3(result.positions[size_t(v)]) + shift, hint, stopSq);
      vertexDist[size_t(v)] = float(std::sqrt(h.distanceSq)), hint = h.face;
    }
  });
  std::vector<float> midDist(nf * 3, 0.0f);
  parallelFor(int64_t(nf), int(threads), 1024, [&](int64_t b, int64_t e) {
    uint32_t hint = UINT32_MAX;
    for (int64_t f = b; f < e; ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = idx[size_t(f) * 3 + size_t(k)], c = idx[size_t(f) * 3 + size_t(k + 1) % 3];
        if (a > c) continue;
        const glm::dvec3 mid = 0.5 * (glm::dvec3(result.positions[a]) + glm::dvec3(result.positions[c])) + shift;
        const auto h = originalBvh.closestUnless(mid, hint, stopSq);
        midDist[size_t(f) * 3 + size_t(k)] = float(std::sqrt(h.distanceSq)), hint = h.face;
      }
  });
  if (isCancelled(progress)) return rep.cancelled = true, finish();
  // A face's worst: its corners, its edges' midpoints (an edge this face
  // runs from the higher vertex to the lower has its midpoint in the face
  // that runs it the other way, found in the lower vertex's fan: a walk of
  // a few faces, where a sorted table of edges cost a binary search of
  // the whole table per edge), and the original vertices nearest to it
  // (below).
  parallelFor(int64_t(nf), int(threads), 1024, [&](int64_t b, int64_t e) {
    for (int64_t f = b; f < e; ++f) {
      float m = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = idx[size_t(f) * 3 + size_t(k)], c = idx[size_t(f) * 3 + size_t(k + 1) % 3];
        m = std::max(m, vertexDist[a]);
        if (a <= c) {
          m = std::max(m, midDist[size_t(f) * 3 + size_t(k)]);
          continue;
        }
        for (uint32_t s = fanStart[c]; s < fanStart[c + 1]; ++s) {
          const uint32_t g = fan[s];
          const int j = idx[size_t(g) * 3] == c ? 0 : idx[size_t(g) * 3 + 1] == c ? 1 : 2;
          if (idx[size_t(g) * 3 + size_t(j + 1) % 3] == a) {
            m = std::max(m, midDist[size_t(g) * 3 + size_t(j)]);
            break;
          }
        }
      }
      faceWorst[size_t(f)] = m;
    }
  });
  // Original vertices by nearest face (counting sort: in vertex order).
  // (None found: a vertex the BVH could not place, e.g. not finite.)
  std::vector<uint32_t> nearStart(nf + 1, 0), nearOf(no);
  for (uint32_t f : nearFace)
    if (f < nf) ++nearStart[f + 1];
  for (size_t f = 0; f < nf; ++f) nearStart[f + 1] += nearStart[f];
  {
    std::vector<uint32_t> fill(nearStart.begin(), nearStart.end() - 1);
    for (size_t i = 0; i < no; ++i)
      if (nearFace[i] < nf) {
        nearOf[fill[nearFace[i]]++] = uint32_t(i);
        faceWorst[nearFace[i]] = std::max(faceWorst[nearFace[i]], nearDist[i]);
      }
  }
  trace.mark("refine: result->original");
  const float largest = *std::max_element(faceWorst.begin(), faceWorst.end());
  rep.largestBefore = rep.largestAfter = largest;
  if (!(largest > 0.0f)) return finish();

  // Candidates: near the largest distance, interior, manifold, one
  // material around, a position of their own, not locked.
  auto localWorst = [&](size_t v) {
    float m = 0.0f;
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) m = std::max(m, faceWorst[fan[s]]);
    return m;
  };
  auto closedFan = [&](size_t v) {
    // Each neighbour follows v in one face and precedes it in another.
    std::vector<uint32_t> next, prev;
    const int mat = material[fan[fanStart[v]]];
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) {
      const uint32_t f = fan[s];
      if (material[f] != mat) return false;
      const int k = idx[f * 3] == v ? 0 : idx[f * 3 + 1] == v ? 1 : 2;
      next.push_back(idx[f * 3 + (k + 1) % 3]);
      prev.push_back(idx[f * 3 + (k + 2) % 3]);
    }
    std::sort(next.begin(), next.end());
    std::sort(prev.begin(), prev.end());
    return next.size() >= 3 && next == prev && std::adjacent_find(next.begin(), next.end()) == next.end();
  };
  std::vector<uint32_t> cand;
  for (size_t v = 0; v < nv; ++v)
    if (fanStart[v + 1] > fanStart[v] && localWorst(v) >= float(opt.candidateShare) * largest && closedFan(v))
      cand.push_back(uint32_t(v));
  // Positions that other vertices, or locked original vertices, hold.
  {
    std::vector<std::pair<uint64_t, uint32_t>> keys(cand.size());
    for (size_t j = 0; j < cand.size(); ++j) keys[j] = {positionKey(result.positions[cand[j]]), uint32_t(j)};
    std::sort(keys.begin(), keys.end());
    std::vector<uint8_t> taken(cand.size(), 0);
    auto mark = [&](const glm::vec3& p, uint32_t self) {
      const uint64_t key = positionKey(p);
      for (auto it = std::lower_bound(keys.begin(), keys.end(), std::pair{key, 0u}); it != keys.end() && it->first == key;
           ++it)
        if (cand[it->second] != self && result.positions[cand[it->second]] == p) taken[it->second] = 1;
    };
    for (size_t v = 0; v < nv; ++v) mark(result.positions[v], uint32_t(v));
    if (opt.lockedOriginalVertices.size() == no)
      for (size_t i = 0; i < no; ++i)
        if (opt.lockedOriginalVertices[i]) mark(glm::vec3(glm::dvec3(original.positions[i]) - shift), UINT32_MAX);
    size_t kept = 0;
    for (size_t j = 0; j < cand.size(); ++j)
      if (!taken[j]) cand[kept++] = cand[j];
    cand.resize(kept);
  }
  rep.candidates = cand.size();
  trace.mark("refine: candidates");
  if (cand.empty()) return finish();
  // The screening's local maxima stand for the candidates' own until they
  // are gathered: a candidate is gathered (its faces sampled densely) only
  // once the screening puts it near the moving gate, so a mesh with many
  // candidates and few that move (a 5M-triangle tile at 50%: 75k and 2k)
  // pays for the few.
  std::vector<double> localMax(cand.size());  // squared, the screening's until gathered
  for (size_t j = 0; j < cand.size(); ++j) localMax[j] = double(localWorst(cand[j])) * double(localWorst(cand[j]));
  // The largest distance away from the candidates (what refining them
  // cannot lower).
  float elsewhere = 0.0f;
  {
    std::vector<uint8_t> isCand(nv, 0);
    for (uint32_t v : cand) isCand[v] = 1;
    for (size_t f = 0; f < nf; ++f)
      if (!isCand[idx[f * 3]] && !isCand[idx[f * 3 + 1]] && !isCand[idx[f * 3 + 2]])
        elsewhere = std::max(elsewhere, faceWorst[f]);
  }

  // The sample grid of a result face, as barycentric weights.
  std::vector<glm::dvec3> grid;
  const int level = std::max(1, opt.sampleLevel);
  for (int i = 0; i <= level; ++i)
    for (int j = 0; j <= level - i; ++j) grid.emplace_back(double(i) / level, double(j) / level, double(level - i - j) / level);

  const double cosTurn = std::cos(opt.maxNormalTurnDeg * 3.14159265358979323846 / 180.0);
  std::vector<double> move(cand.size(), 0.0), best(cand.size(), 0.0);
  std::vector<uint8_t> gathered(cand.size(), 0);
  std::vector<glm::dvec3> normal(cand.size());
  std::vector<uint8_t> movedOnce(cand.size(), 0);
  std::vector<uint32_t> candOf(nv, UINT32_MAX);
  for (size_t j = 0; j < cand.size(); ++j) candOf[cand[j]] = uint32_t(j);
  auto corner = [&](uint32_t f, int k) { return glm::dvec3(result.positions[idx[size_t(f) * 3 + size_t(k)]]); };

  // The faces around the candidates, and what a round measures on each:
  // the vector from each grid sample to the original's nearest point, and
  // from the nearest point of the face to each original vertex whose
  // nearest face it was at the screening, with that point's weights.
  std::vector<uint32_t> active, slotOf(nf, UINT32_MAX);
  for (uint32_t v : cand)
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s)
      if (slotOf[fan[s]] == UINT32_MAX) slotOf[fan[s]] = uint32_t(active.size()), active.push_back(fan[s]);
  std::sort(active.begin(), active.end());
  for (size_t a = 0; a < active.size(); ++a) slotOf[active[a]] = uint32_t(a);
  std::vector<size_t> nearFrom(active.size() + 1, 0);
  for (size_t a = 0; a < active.size(); ++a) nearFrom[a + 1] = nearFrom[a] + (nearStart[active[a] + 1] - nearStart[active[a]]);
  const size_t gn = grid.size();
  std::vector<glm::vec3> backE(active.size() * gn);
  // Whether a face, corners given in the result's frame, faces against
  // the original surface at its centre: the error report's own flip test
  // (ErrorMeter::facing), so that a face the report does not count as
  // flipped is never turned into one it does (a test of the original's
  // normal at a nearby sample disagreed with it on faces nearly across the
  // surface).
  auto facesAgainst = [&](const glm::dvec3 (&c)[3]) { return meter.facing(c[0] + shift, c[1] + shift, c[2] + shift).against; };
  std::vector<uint8_t> against(active.size(), 0);  // as measured with the face's current corners
  struct Near {
    glm::vec3 e, bary;
  };
  std::vector<Near> nearE(nearFrom.back());
  // Faces measured at the current positions (none at first), and those to
  // measure in this round.
  std::vector<uint8_t> fresh(active.size(), 0), wanted(active.size(), 0);
  std::vector<uint32_t> todo;
  auto measureFaces = [&] {
    todo.clear();
    for (size_t a = 0; a < active.size(); ++a)
      if (wanted[a] && !fresh[a]) todo.push_back(uint32_t(a)), fresh[a] = 1;
    parallelFor(int64_t(todo.size()), int(threads), 64, [&](int64_t b, int64_t e) {
      std::vector<glm::dvec3> pts(gn);
      std::vector<ClosestPointBvh::Hit> hits(gn);
      ClosestPointBvh::ManyScratch scratch;
      uint32_t hint = UINT32_MAX;
      for (int64_t i = b; i < e; ++i) {
        const size_t a = todo[size_t(i)];
        const uint32_t f = active[a];
        const glm::dvec3 c0 = corner(f, 0), c1 = corner(f, 1), c2 = corner(f, 2);
        for (size_t g = 0; g < gn; ++g) pts[g] = grid[g].x * c0 + grid[g].y * c1 + grid[g].z * c2 + shift;
        hint = originalBvh.closestMany(pts, hint, hits, scratch);
        for (size_t g = 0; g < gn; ++g) backE[a * gn + g] = glm::vec3(hits[g].point - pts[g]);
        {
          const glm::dvec3 now[3] = {c0, c1, c2};
          against[a] = facesAgainst(now);
        }
        for (uint32_t s = nearStart[f], t = 0; s < nearStart[f + 1]; ++s, ++t) {
          const glm::dvec3 p = glm::dvec3(original.positions[nearOf[s]]) - shift;
          glm::dvec3 q, bary;
          closestPointOnTriangle(p, c0, c1, c2, q, bary);
          nearE[nearFrom[a] + t] = {glm::vec3(p - q), glm::vec3(bary)};
        }
      }
    });
  };

  // Candidate j's samples at the positions measureFaces() saw; returns its
  // local maximum (squared), leaving its samples in `cs`.
  auto gather = [&](size_t j, std::vector<Constraint>& cs, glm::dvec3& n) {
    const uint32_t v = cand[j];
    cs.clear();
    glm::dvec3 sum(0.0);
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) {
      const uint32_t f = fan[s];
      sum += glm::cross(corner(f, 1) - corner(f, 0), corner(f, 2) - corner(f, 0));
    }
    const double len = glm::length(sum);
    n = len > 0 ? sum / len : glm::dvec3(0.0);
    if (!(len > 0)) return 0.0;
    auto add = [&](const glm::vec3& ef, double w) {
      if (!(w > 0)) return;
      const glm::dvec3 e(ef);
      const double along = glm::dot(e, n);
      cs.push_back({std::max(0.0, glm::dot(e, e) - along * along), along, w});
    };
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) {
      const uint32_t f = fan[s], a = slotOf[f];
      const int k = idx[size_t(f) * 3] == v ? 0 : idx[size_t(f) * 3 + 1] == v ? 1 : 2;
      for (size_t g = 0; g < gn; ++g) add(backE[size_t(a) * gn + g], grid[g][k]);
      for (size_t t = nearFrom[a]; t < nearFrom[a + 1]; ++t) add(nearE[t].e, double(nearE[t].bary[k]));
    }
    return worst(cs, 0.0);
  };

  // Face f with its corners moved by shiftOf(corner): within the turn
  // limit of how it is now, and not turned against the original surface
  // if it faced along it. The moved corners are rounded to float as they
  // will be stored, so the test sees what the report will.
  auto faceStaysFair = [&](uint32_t f, auto&& shiftOf) {
    glm::dvec3 c[3] = {corner(f, 0), corner(f, 1), corner(f, 2)};
    const glm::dvec3 before = glm::cross(c[1] - c[0], c[2] - c[0]);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 stored(c[k] + shiftOf(idx[size_t(f) * 3 + size_t(k)]));
      c[k] = reloaded(stored);
    }
    const glm::dvec3 after = glm::cross(c[1] - c[0], c[2] - c[0]);
    const double lb = glm::length(before), la = glm::length(after);
    if (!(lb > 0 && la > 0 && glm::dot(before, after) >= cosTurn * lb * la)) return false;
    if (!opt.keepFacingOriginal || against[slotOf[f]]) return true;
    return !facesAgainst(c);
  };

  // Largest move that keeps every face around v fair (alone; halved up
  // to four times), or 0.
  auto safeMove = [&](uint32_t v, const glm::dvec3& n, double d) {
    double shortest = HUGE_VAL;
    for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) {
      const uint32_t f = fan[s];
      for (int k = 0; k < 3; ++k) shortest = std::min(shortest, glm::length(corner(f, (k + 1) % 3) - corner(f, k)));
    }
    d = std::clamp(d, -opt.maxMoveEdgeShare * shortest, opt.maxMoveEdgeShare * shortest);
    for (int attempt = 0; attempt < 5; ++attempt, d *= 0.5) {
      bool ok = true;
      for (uint32_t s = fanStart[v]; s < fanStart[v + 1] && ok; ++s)
        ok = faceStaysFair(fan[s], [&](uint32_t w) { return w == v ? d * n : glm::dvec3(0.0); });
      if (ok) return d;
    }
    return 0.0;
  };

  const size_t count = cand.size();
  for (int round = 0; round <= opt.iterations; ++round) {
    const bool last = round == opt.iterations;  // the last pass only measures
    // Who is gathered: those gathered before whose faces moved since (the
    // rest keep their samples), and those the screening now puts within
    // reach of the gate (the last, measuring pass only the former).
    double estimate = double(elsewhere) * double(elsewhere);
    for (double m : localMax) estimate = std::max(estimate, m);
    const double reachGate = 0.8 * 0.8 * opt.moveShare * opt.moveShare * estimate;
    std::vector<uint8_t> want(count, 0);
    std::fill(wanted.begin(), wanted.end(), 0);
    for (size_t j = 0; j < count; ++j) {
      const uint32_t v = cand[j];
      bool changed = false;
      for (uint32_t s = fanStart[v]; s < fanStart[v + 1] && !changed; ++s) changed = !fresh[slotOf[fan[s]]];
      want[j] = gathered[j] ? changed : !last && localMax[j] >= reachGate;
      if (want[j])
        for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) wanted[slotOf[fan[s]]] = 1;
    }
    measureFaces();
    trace.mark("refine: measure faces");
    parallelFor(int64_t(count), int(threads), 16, [&](int64_t b, int64_t e) {
      std::vector<Constraint> cs;
      for (int64_t j = b; j < e; ++j) {
        if (!want[size_t(j)]) continue;
        gathered[size_t(j)] = 1;
        glm::dvec3 n;
        localMax[size_t(j)] = gather(size_t(j), cs, n);
        normal[size_t(j)] = n;
        best[size_t(j)] = 0.0;
        if (last || cs.empty()) continue;
        const double reach = 2.0 * std::sqrt(localMax[size_t(j)]);
        double d = minimaxMove(cs, reach);
        if (opt.leastSquaresSlack > 0) d = towardsLeastSquares(cs, d, reach, opt.leastSquaresSlack);
        best[size_t(j)] = worst(cs, d) < localMax[size_t(j)] ? d : 0.0;
      }
    });
    trace.mark("refine: gather+solve");
    if (isCancelled(progress)) return rep.cancelled = true, finish();
    double roundMax = double(elsewhere) * double(elsewhere);
    for (double m : localMax) roundMax = std::max(roundMax, m);
    if (round == 0) rep.largestBefore = std::sqrt(roundMax);
    rep.largestAfter = std::sqrt(roundMax);
    if (last) break;
    const double gate = opt.moveShare * opt.moveShare * roundMax;
    size_t moves = 0;
    parallelFor(int64_t(count), int(threads), 64, [&](int64_t b, int64_t e) {
      for (int64_t j = b; j < e; ++j) {
        const size_t k = size_t(j);
        move[k] = gathered[k] && best[k] != 0.0 && localMax[k] >= gate ? safeMove(cand[k], normal[k], opt.damping * best[k]) : 0.0;
      }
    });
    trace.mark("refine: safe moves");
    // Neighbours move in the same round: a face with two or three moving
    // corners is checked with all their moves, and where it would not
    // stay fair its moving corners move half as far (after four halvings,
    // not at all), until every face is fair.
    auto shiftOf = [&](uint32_t w) {
      const uint32_t j = candOf[w];
      return j != UINT32_MAX && move[j] != 0.0 ? move[j] * normal[j] : glm::dvec3(0.0);
    };
    std::vector<uint8_t> halved(count, 0);
    for (bool again = true; again;) {
      again = false;
      for (size_t j = 0; j < count; ++j) {
        if (move[j] == 0.0) continue;
        const uint32_t v = cand[j];
        for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) {
          const uint32_t f = fan[s];
          if (faceStaysFair(f, shiftOf)) continue;
          for (int k = 0; k < 3; ++k)
            if (const uint32_t c = candOf[idx[size_t(f) * 3 + size_t(k)]]; c != UINT32_MAX && move[c] != 0.0)
              move[c] = ++halved[c] > 4 ? 0.0 : 0.5 * move[c], again = true;
          break;
        }
      }
    }
    trace.mark("refine: conflicts");
    for (size_t j = 0; j < count; ++j)
      if (move[j] != 0.0) {
        const uint32_t v = cand[j];
        for (uint32_t s = fanStart[v]; s < fanStart[v + 1]; ++s) fresh[slotOf[fan[s]]] = 0;
        result.positions[v] = glm::vec3(glm::dvec3(result.positions[v]) + move[j] * normal[j]);
        movedOnce[j] = 1, ++moves;
      }
    rep.iterations = round + 1;
    reportProgress(progress, double(round + 1) / double(opt.iterations + 1), "Refining vertices");
    if (moves == 0) break;
  }
  for (uint8_t m : movedOnce) rep.moved += m;
  if (rep.moved) computeVertexNormals(result, threads);
  reportProgress(progress, 1.0, "Refined");
  return finish();
}

}  // namespace hs::mesh
