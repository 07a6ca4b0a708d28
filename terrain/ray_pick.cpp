#include "terrain/ray_pick.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {
namespace {

// Möller–Trumbore in double; returns the ray parameter or a negative value.
double hitTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                   const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-18) return -1.0;
  const double inv = 1.0 / det;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) * inv;
  if (u < -1e-9 || u > 1.0 + 1e-9) return -1.0;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) * inv;
  if (v < -1e-9 || u + v > 1.0 + 1e-9) return -1.0;
  return glm::dot(e2, q) * inv;
}

// Clips the ray to [lo, hi] on one axis; false if it misses.
bool clipAxis(double o, double d, double lo, double hi, double& t0, double& t1) {
  if (std::abs(d) < 1e-300) return o >= lo && o <= hi;
  double a = (lo - o) / d, b = (hi - o) / d;
  if (a > b) std::swap(a, b);
  t0 = std::max(t0, a);
  t1 = std::min(t1, b);
  return t0 <= t1;
}

// 2D grid walk (Amanatides & Woo) in sample units along p(t) = P + t*D for
// t in [tStart, tEnd]; cells of size `cell`, indices clamped to [0, n).
template <class Visit>
bool walk(const glm::dvec2& P, const glm::dvec2& D, double tStart, double tEnd, double cell, int nx, int ny,
          Visit&& visit) {
  const glm::dvec2 p = P + tStart * D;
  int ix = std::clamp(int(std::floor(p.x / cell)), 0, nx - 1);
  int iy = std::clamp(int(std::floor(p.y / cell)), 0, ny - 1);
  const int stepX = D.x > 0 ? 1 : -1, stepY = D.y > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  double tMaxX = D.x > 0 ? ((ix + 1) * cell - P.x) / D.x : D.x < 0 ? (ix * cell - P.x) / D.x : inf;
  double tMaxY = D.y > 0 ? ((iy + 1) * cell - P.y) / D.y : D.y < 0 ? (iy * cell - P.y) / D.y : inf;
  const double dX = D.x != 0 ? cell / std::abs(D.x) : inf, dY = D.y != 0 ? cell / std::abs(D.y) : inf;
  double tIn = tStart;
  for (int guard = 0; guard < 4 * (nx + ny) + 8; ++guard) {
    const double tOut = std::min({tMaxX, tMaxY, tEnd});
    if (visit(ix, iy, tIn, tOut)) return true;
    if (tOut >= tEnd) return false;
    if (tMaxX < tMaxY) {
      ix += stepX;
      tIn = tMaxX;
      tMaxX += dX;
    } else {
      iy += stepY;
      tIn = tMaxY;
      tMaxY += dY;
    }
    if (ix < 0 || iy < 0 || ix >= nx || iy >= ny) return false;
  }
  return false;
}

}  // namespace

std::optional<RayHit> intersectRay(const Heightfield& hf, const glm::dvec3& worldOrigin,
                                   const glm::dvec3& direction, double maxDistance) {
  const double len = glm::length(direction);
  if (!(len > 0.0) || !std::isfinite(len) || hf.samplesX() < 2) return std::nullopt;
  const glm::dvec3 d = direction / len;
  const glm::dvec3 o = worldOrigin - hf.origin();  // local metres
  if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) return std::nullopt;
  const glm::dvec2 sp = hf.spacing();
  const HeightRange all = hf.range();
  double t0 = 0.0, t1 = std::isfinite(maxDistance) ? maxDistance : 1e300;
  const glm::dvec2 ext = hf.sizeMetres();
  if (!clipAxis(o.x, d.x, 0.0, ext.x, t0, t1) || !clipAxis(o.y, d.y, 0.0, ext.y, t0, t1) ||
      !clipAxis(o.z, d.z, double(all.min) - 1e-3, double(all.max) + 1e-3, t0, t1))
    return std::nullopt;

  const glm::dvec2 P(o.x / sp.x, o.y / sp.y), D(d.x / sp.x, d.y / sp.y);
  const int cellsX = hf.samplesX() - 1, cellsY = hf.samplesY() - 1;
  const int tilesX = hf.heights().tilesX();
  const int tnx = (cellsX + kTileSize - 1) / kTileSize, tny = (cellsY + kTileSize - 1) / kTileSize;

  std::optional<RayHit> best;
  walk(P, D, t0, t1, double(kTileSize), tnx, tny, [&](int tx, int ty, double tIn, double tOut) {
    const HeightRange b = hf.tileBounds(ty * tilesX + tx);
    const double za = o.z + tIn * d.z, zb = o.z + tOut * d.z;
    if (std::min(za, zb) > double(b.max) + 1e-6 || std::max(za, zb) < double(b.min) - 1e-6) return false;
    // Walk the cells of this tile over [tIn, tOut].
    const int cx0 = tx * kTileSize, cy0 = ty * kTileSize;
    const int ncx = std::min(kTileSize, cellsX - cx0), ncy = std::min(kTileSize, cellsY - cy0);
    const glm::dvec2 Pt = P - glm::dvec2(cx0, cy0);
    return walk(Pt, D, tIn, tOut, 1.0, ncx, ncy, [&](int lx, int ly, double, double) {
      const int cx = cx0 + lx, cy = cy0 + ly;
      if (hf.cellIsHole(cx, cy)) return false;
      const glm::dvec3 p00(cx * sp.x, cy * sp.y, double(hf.at(cx, cy)));
      const glm::dvec3 p10((cx + 1) * sp.x, cy * sp.y, double(hf.at(cx + 1, cy)));
      const glm::dvec3 p01(cx * sp.x, (cy + 1) * sp.y, double(hf.at(cx, cy + 1)));
      const glm::dvec3 p11((cx + 1) * sp.x, (cy + 1) * sp.y, double(hf.at(cx + 1, cy + 1)));
      double tBest = -1.0;
      glm::dvec3 n(0, 0, 1);
      const double ta = hitTriangle(o, d, p00, p10, p11);
      if (ta >= 0.0) {
        tBest = ta;
        n = glm::cross(p10 - p00, p11 - p00);
      }
      const double tb = hitTriangle(o, d, p00, p11, p01);
      if (tb >= 0.0 && (tBest < 0.0 || tb < tBest)) {
        tBest = tb;
        n = glm::cross(p11 - p00, p01 - p00);
      }
      if (tBest < 0.0 || tBest > t1) return false;
      RayHit h;
      h.distance = tBest;
      const glm::dvec3 local = o + tBest * d;
      h.local = glm::dvec2(local);
      h.world = hf.origin() + local;
      h.normal = glm::vec3(glm::normalize(n.z < 0 ? -n : n));
      h.cellX = cx;
      h.cellY = cy;
      best = h;
      return true;
    });
  });
  return best;
}

}  // namespace hs::terrain
