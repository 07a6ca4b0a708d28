#pragma once
// The one-dimensional move of the minimax refinement (max_error_refine.h):
// where along its normal a vertex goes, given its samples' distances as
// functions of the move. Pure functions, tested against brute force
// (test_meshproc_refine).
#include <algorithm>
#include <vector>

namespace hs::mesh::minimax {

// One sample's distance after a move d along the vertex normal:
// sqrt(across + (along - weight d)^2).
struct Constraint {
  double across, along, weight;
};

// The largest squared distance over the samples after a move d.
inline double worst(const std::vector<Constraint>& cs, double d) {
  double m = 0.0;
  for (const Constraint& c : cs) {
    const double a = c.along - c.weight * d;
    m = std::max(m, c.across + a * a);
  }
  return m;
}

// The move in [-reach, reach] that minimises the largest squared distance
// (convex in d: a maximum of convex parabolas), by ternary search; ties
// (a flat bottom) go towards 0 through a vanishing pull.
inline double minimaxMove(const std::vector<Constraint>& cs, double reach) {
  const double pull = 1e-9;
  auto f = [&](double d) { return worst(cs, d) + pull * d * d; };
  double lo = -reach, hi = reach;
  for (int i = 0; i < 60; ++i) {
    const double a = lo + (hi - lo) / 3.0, b = hi - (hi - lo) / 3.0;
    if (f(a) < f(b))
      hi = b;
    else
      lo = a;
  }
  return 0.5 * (lo + hi);
}

// Of the moves whose largest distance is within `slack` of the minimax
// move's (a share of it), the one nearest to the least-squares move (the
// least sum of squared distances): the largest distance stays where the
// minimax put it, give or take the slack, and the others pay less for it.
inline double towardsLeastSquares(const std::vector<Constraint>& cs, double minimax, double reach, double slack) {
  double sw = 0.0, swa = 0.0;
  for (const Constraint& c : cs) sw += c.weight * c.weight, swa += c.weight * c.along;
  if (!(sw > 0)) return minimax;
  const double ls = std::clamp(swa / sw, -reach, reach);
  const double allowed = (1.0 + slack) * (1.0 + slack) * worst(cs, minimax);
  if (worst(cs, ls) <= allowed) return ls;
  // worst() is convex with its least at `minimax`: it grows from there
  // towards `ls`, and the last move within the allowance lies between.
  double in = minimax, out = ls;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (in + out);
    (worst(cs, mid) <= allowed ? in : out) = mid;
  }
  return in;
}

}  // namespace hs::mesh::minimax
