#pragma once
// Error quadrics (Garland & Heckbert 1997): Q(p) = p'Ap + 2b'p + c is the
// weighted sum of squared distances from p to a set of planes. Summing the
// quadrics of two vertices gives the error of merging them, and the p that
// minimises Q is the "optimal placement" of the merged vertex.
//
// Arithmetic in double: with centimetre errors on a mesh metres across,
// the three terms of Q cancel to 8 or more digits when the frame's origin
// is far from the planes. Stored per vertex as QuadricF, relative to the
// vertex (below), where they do not.
#include <cmath>

#include <glm/glm.hpp>

namespace hs::mesh {

// Trivially constructible on purpose (arrays of millions are allocated
// without zeroing and filled in parallel): write `Quadric q{}` for zero.
struct Quadric {
  double a00, a01, a02, a11, a12, a22;
  double b0, b1, b2;
  double c;
  double weight;  // sum of plane weights: Q / weight is a mean squared distance

  // Plane n.p + d = 0 (n unit length) with weight w.
  static Quadric plane(const glm::dvec3& n, double d, double w) {
    Quadric q{};
    q.a00 = w * n.x * n.x, q.a01 = w * n.x * n.y, q.a02 = w * n.x * n.z;
    q.a11 = w * n.y * n.y, q.a12 = w * n.y * n.z, q.a22 = w * n.z * n.z;
    q.b0 = w * d * n.x, q.b1 = w * d * n.y, q.b2 = w * d * n.z;
    q.c = w * d * d;
    q.weight = w;
    return q;
  }

  Quadric& operator+=(const Quadric& o) {
    a00 += o.a00, a01 += o.a01, a02 += o.a02, a11 += o.a11, a12 += o.a12, a22 += o.a22;
    b0 += o.b0, b1 += o.b1, b2 += o.b2;
    c += o.c;
    weight += o.weight;
    return *this;
  }
  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

  // The same quadric in a frame whose origin sits at `t` in this one
  // (Q'(x) = Q(x + t)): b' = b + A t, c' = Q(t). With t an edge length,
  // nothing large cancels.
  Quadric translated(const glm::dvec3& t) const {
    Quadric q = *this;
    q.b0 = b0 + a00 * t.x + a01 * t.y + a02 * t.z;
    q.b1 = b1 + a01 * t.x + a11 * t.y + a12 * t.z;
    q.b2 = b2 + a02 * t.x + a12 * t.y + a22 * t.z;
    q.c = evaluate(t);
    return q;
  }

  double evaluate(const glm::dvec3& p) const {
    const double x = p.x, y = p.y, z = p.z;
    const double r = x * (a00 * x + 2 * (a01 * y + a02 * z + b0)) + y * (a11 * y + 2 * (a12 * z + b1)) +
                     z * (a22 * z + 2 * b2) + c;
    return r > 0 ? r : 0.0;  // rounding can dip below zero on exact fits
  }

  // Minimiser of Q(p) + eps |p - anchor|^2 with eps a small multiple of the
  // quadric's scale. The small pull towards `anchor` (the edge midpoint)
  // makes flat and cylindrical regions, where A is singular and any point
  // along a line or plane is optimal, choose the point nearest the edge
  // instead of failing over to a fixed candidate; where A is well
  // conditioned the pull moves p by a negligible amount. eps = 1e-6 of the
  // trace: A's eigenvalues along a gently curved or noisy surface are
  // about trace x (the spread of the face normals)^2, 1e-4 of it for
  // millimetre noise on 17 cm faces, and the 1e-3 this used to be
  // outweighed them, holding the placement at the midpoint where the
  // surface asked for another point (docs/meshes.md, "Quad-dominant
  // meshes"). 1e-6 is still 16x the float rounding of a stored A
  // (QuadricF), so a direction that is singular stays regularised.
  // Returns false only for an empty quadric.
  bool minimize(const glm::dvec3& anchor, glm::dvec3& p) const {
    const double trace = a00 + a11 + a22;
    if (!(trace > 0)) return false;
    const double eps = 1e-6 * trace;
    const double m00 = a00 + eps, m11 = a11 + eps, m22 = a22 + eps;
    const double r0 = -b0 + eps * anchor.x, r1 = -b1 + eps * anchor.y, r2 = -b2 + eps * anchor.z;
    // Symmetric 3x3 solve by cofactors.
    const double c00 = m11 * m22 - a12 * a12;
    const double c01 = a02 * a12 - a01 * m22;
    const double c02 = a01 * a12 - a02 * m11;
    const double det = m00 * c00 + a01 * c01 + a02 * c02;
    if (!(std::abs(det) > 0)) return false;
    const double c11 = m00 * m22 - a02 * a02;
    const double c12 = a01 * a02 - m00 * a12;
    const double c22 = m00 * m11 - a01 * a01;
    const double inv = 1.0 / det;
    p = glm::dvec3((c00 * r0 + c01 * r1 + c02 * r2) * inv, (c01 * r0 + c11 * r1 + c12 * r2) * inv,
                   (c02 * r0 + c12 * r1 + c22 * r2) * inv);
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  }
};

// Where the vertex that merges edge (a, b) goes, and Q there: the
// quadric's optimum when it lies within one edge length of the midpoint;
// beyond that the quadric is near-singular in some direction and the
// cheapest of the midpoint and the two ends is the safer choice. The
// decimator's rule (CollapseEngine::evaluate), shared with the benchmarks'
// prototypes so that they place vertices as it does.
inline double placeOnEdge(const Quadric& q, const glm::dvec3& a, const glm::dvec3& b, glm::dvec3& p) {
  const glm::dvec3 mid = 0.5 * (a + b), ab = b - a;
  if (q.minimize(mid, p) && glm::dot(p - mid, p - mid) <= glm::dot(ab, ab)) return q.evaluate(p);
  p = mid;
  double cost = q.evaluate(mid);
  const double ea = q.evaluate(a), eb = q.evaluate(b);
  if (ea < cost) p = a, cost = ea;
  if (eb < cost) p = b, cost = eb;
  return cost;
}

// A quadric stored in single precision relative to its own vertex (the
// decimator's per-vertex record; arithmetic is done in double after
// load()). Relative to the vertex, every term is of the size of the
// errors being measured: b and c come from the planes' distances to the
// vertex, not to a centre hundreds of metres away, where c alone would be
// 6e4 m^2 against errors of 1e-4 m^2 and float could not hold the
// difference. A's entries have float's 6e-8 relative error, so Q(x)/weight
// is off by at most about 1e-7 |x|^2 at an offset x from the vertex: for
// the edge lengths evaluated, 1000x below the heap key's length term.
struct QuadricF {
  float a00, a01, a02, a11, a12, a22;
  float b0, b1, b2;
  float c;
  float weight;

  static QuadricF store(const Quadric& q) {
    return {float(q.a00), float(q.a01), float(q.a02), float(q.a11), float(q.a12), float(q.a22),
            float(q.b0),  float(q.b1),  float(q.b2),  float(q.c),   float(q.weight)};
  }
  Quadric load() const {
    return {double(a00), double(a01), double(a02), double(a11), double(a12), double(a22),
            double(b0),  double(b1),  double(b2),  double(c),   double(weight)};
  }
};

}  // namespace hs::mesh
