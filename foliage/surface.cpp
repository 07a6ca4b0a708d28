#include "foliage/surface.h"

#include <algorithm>
#include <cmath>

namespace hs::foliage {

double slopeDegrees(const glm::dvec3& n) {
  const double h = std::hypot(n.x, n.y);
  if (h == 0.0) return n.z >= 0.0 ? 0.0 : 180.0;
  if (n.z == 0.0) return 90.0;
  return std::atan2(h, n.z) * (180.0 / 3.14159265358979323846);
}

namespace {

// The triangle of cell (x0, y0) under fractions (tx, ty) and its
// interpolation: h = a + tx * dx + ty * dy.
struct Tri {
  double a, dx, dy;
};
template <class F>
Tri cellTriangle(F value, int x0, int y0, double tx, double ty) {
  const double v00 = value(x0, y0), v10 = value(x0 + 1, y0), v01 = value(x0, y0 + 1), v11 = value(x0 + 1, y0 + 1);
  if (tx >= ty) return {v00, v10 - v00, v11 - v10};
  return {v00, v11 - v01, v01 - v00};
}

bool cellAt(const terrain::Heightfield& hf, const glm::dvec2& world, int& x0, int& y0, double& tx, double& ty) {
  const glm::dvec2 s = (world - glm::dvec2(hf.origin())) / hf.spacing();
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x <= hf.samplesX() - 1 && s.y <= hf.samplesY() - 1)) return false;
  x0 = std::min(int(s.x), hf.samplesX() - 2);
  y0 = std::min(int(s.y), hf.samplesY() - 2);
  tx = s.x - x0;
  ty = s.y - y0;
  return true;
}

}  // namespace

std::optional<SurfacePoint> terrainSurface(const terrain::Heightfield& hf, const glm::dvec2& world) {
  int x0, y0;
  double tx, ty;
  if (!cellAt(hf, world, x0, y0, tx, ty) || hf.cellIsHole(x0, y0)) return std::nullopt;
  const Tri t = cellTriangle([&](int x, int y) { return double(hf.at(x, y)); }, x0, y0, tx, ty);
  SurfacePoint p;
  p.position = {world.x, world.y, hf.origin().z + t.a + tx * t.dx + ty * t.dy};
  const glm::dvec3 n(-t.dx / hf.spacing().x, -t.dy / hf.spacing().y, 1.0);
  p.normal = glm::normalize(n);
  p.slopeDeg = slopeDegrees(n);
  p.surface = Surface::Terrain;
  return p;
}

double terrainLayerWeight(const terrain::Terrain& t, int layer, const glm::dvec2& world) {
  int x0, y0;
  double tx, ty;
  if (layer < 0 || layer >= t.paint.layerCount() || !cellAt(t.height, world, x0, y0, tx, ty)) return 0.0;
  const Tri tri = cellTriangle([&](int x, int y) { return double(t.paint.raw(layer, x, y)); }, x0, y0, tx, ty);
  return (tri.a + tx * tri.dx + ty * tri.dy) / double(terrain::kWeightOne);
}

int terrainLayerIndex(const terrain::Terrain& t, const std::string& name) {
  for (int i = 0; i < t.paint.layerCount(); ++i)
    if (t.paint.material(i).name == name) return i;
  return -1;
}

// --- meshes -----------------------------------------------------------------------

MeshGround::MeshGround(const mesh::MeshData& mesh) : mesh_(&mesh), bvh_(mesh) {
  const size_t n = mesh.triangleCount();
  area_.resize(n);
  faceNormal_.resize(n);
  lo_ = glm::dvec2(std::numeric_limits<double>::max());
  hi_ = glm::dvec2(std::numeric_limits<double>::lowest());
  for (size_t f = 0; f < n; ++f) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * f]]), b(mesh.positions[mesh.indices[3 * f + 1]]),
        c(mesh.positions[mesh.indices[3 * f + 2]]);
    const glm::dvec3 cr = glm::cross(b - a, c - a);
    const double len = glm::length(cr);
    area_[f] = 0.5 * len;
    faceNormal_[f] = len > 0.0 ? cr / len : glm::dvec3(0.0);
    for (const glm::dvec3& v : {a, b, c}) {
      lo_ = glm::min(lo_, glm::dvec2(v) + glm::dvec2(mesh.origin));
      hi_ = glm::max(hi_, glm::dvec2(v) + glm::dvec2(mesh.origin));
    }
  }
  if (n == 0) {
    lo_ = hi_ = glm::dvec2(mesh.origin);
    binStart_.assign(2, 0);
    return;
  }
  // Bins of about 4 triangles each, at most 2^22 of them.
  const glm::dvec2 ext = glm::max(hi_ - lo_, glm::dvec2(1e-6));
  bin_ = std::max(std::sqrt(ext.x * ext.y * 4.0 / double(n)), std::sqrt(ext.x * ext.y / double(1 << 22)));
  binsX_ = std::max(1, int(std::ceil(ext.x / bin_)));
  binsY_ = std::max(1, int(std::ceil(ext.y / bin_)));
  std::vector<uint32_t> counts(size_t(binsX_) * size_t(binsY_) + 1, 0);
  auto range = [&](size_t f, int& bx0, int& by0, int& bx1, int& by1) {
    glm::dvec2 l(std::numeric_limits<double>::max()), h(std::numeric_limits<double>::lowest());
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 v = glm::dvec2(glm::dvec3(mesh.positions[mesh.indices[3 * f + size_t(k)]])) + glm::dvec2(mesh.origin);
      l = glm::min(l, v);
      h = glm::max(h, v);
    }
    bx0 = std::clamp(int((l.x - lo_.x) / bin_), 0, binsX_ - 1);
    by0 = std::clamp(int((l.y - lo_.y) / bin_), 0, binsY_ - 1);
    bx1 = std::clamp(int((h.x - lo_.x) / bin_), 0, binsX_ - 1);
    by1 = std::clamp(int((h.y - lo_.y) / bin_), 0, binsY_ - 1);
  };
  for (size_t f = 0; f < n; ++f) {
    int bx0, by0, bx1, by1;
    range(f, bx0, by0, bx1, by1);
    for (int y = by0; y <= by1; ++y)
      for (int x = bx0; x <= bx1; ++x) ++counts[size_t(y) * size_t(binsX_) + size_t(x)];
  }
  binStart_.assign(counts.size(), 0);
  for (size_t i = 1; i < counts.size(); ++i) binStart_[i] = binStart_[i - 1] + counts[i - 1];
  binFaces_.resize(binStart_.back());
  std::vector<uint32_t> fill(binStart_.begin(), binStart_.end() - 1);
  for (size_t f = 0; f < n; ++f) {
    int bx0, by0, bx1, by1;
    range(f, bx0, by0, bx1, by1);
    for (int y = by0; y <= by1; ++y)
      for (int x = bx0; x <= bx1; ++x) binFaces_[fill[size_t(y) * size_t(binsX_) + size_t(x)]++] = uint32_t(f);
  }
}

void MeshGround::trianglesIn(const glm::dvec2& lo, const glm::dvec2& hi, std::vector<uint32_t>& out) const {
  out.clear();
  if (binFaces_.empty() || hi.x < lo_.x || hi.y < lo_.y || lo.x > hi_.x || lo.y > hi_.y) return;
  const int bx0 = std::clamp(int((lo.x - lo_.x) / bin_), 0, binsX_ - 1);
  const int by0 = std::clamp(int((lo.y - lo_.y) / bin_), 0, binsY_ - 1);
  const int bx1 = std::clamp(int((hi.x - lo_.x) / bin_), 0, binsX_ - 1);
  const int by1 = std::clamp(int((hi.y - lo_.y) / bin_), 0, binsY_ - 1);
  for (int y = by0; y <= by1; ++y)
    for (int x = bx0; x <= bx1; ++x) {
      const size_t b = size_t(y) * size_t(binsX_) + size_t(x);
      out.insert(out.end(), binFaces_.begin() + binStart_[b], binFaces_.begin() + binStart_[b + 1]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

SurfacePoint MeshGround::pointOn(uint32_t face, const glm::dvec3& bary) const {
  const mesh::MeshData& m = *mesh_;
  const glm::dvec3 a(m.positions[m.indices[3 * size_t(face)]]), b(m.positions[m.indices[3 * size_t(face) + 1]]),
      c(m.positions[m.indices[3 * size_t(face) + 2]]);
  SurfacePoint p;
  p.position = m.origin + (a * bary.x + b * bary.y + c * bary.z);
  p.normal = faceNormal_[face];
  p.slopeDeg = slopeDegrees(glm::cross(b - a, c - a));
  p.surface = Surface::Mesh;
  return p;
}

std::optional<SurfacePoint> MeshGround::closest(const glm::dvec3& world, double maxDistance) const {
  if (bvh_.empty()) return std::nullopt;
  const mesh::ClosestPointBvh::Hit h = bvh_.closest(world - mesh_->origin);
  if (!h.found() || h.distanceSq > maxDistance * maxDistance) return std::nullopt;
  SurfacePoint p = pointOn(h.face, h.bary);
  p.position = mesh_->origin + h.point;
  return p;
}

bool MeshGround::covers(const glm::dvec3& world, double height) const {
  if (bvh_.empty() || world.x < lo_.x || world.y < lo_.y || world.x > hi_.x || world.y > hi_.y) return false;
  return bvh_.occluded(world - mesh_->origin + glm::dvec3(0.0, 0.0, 0.01), glm::dvec3(0.0, 0.0, 1.0), 0.0, height);
}

std::optional<SurfacePoint> MeshGround::raycast(const glm::dvec3& origin, const glm::dvec3& direction,
                                                double maxDistance) const {
  if (bvh_.empty() || !(maxDistance > 0.0)) return std::nullopt;
  const double far = std::min(maxDistance, 1e8);  // an infinite one cannot be halved
  const glm::dvec3 o = origin - mesh_->origin;
  if (!bvh_.occluded(o, direction, 0.0, far)) return std::nullopt;
  // Invariant: a triangle is crossed within [lo, hi], none before lo.
  double lo = 0.0, hi = far;
  for (int i = 0; i < 64 && hi - lo > 1e-3; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (bvh_.occluded(o, direction, lo, mid)) hi = mid;
    else lo = mid;
  }
  // The crossed triangle is within 1 mm of the point: its closest point
  // gives the face's normal and slope.
  return closest(origin + direction * hi, 1e-2);
}

// --- ground and regions ------------------------------------------------------------

void Ground::bounds(glm::dvec2& lo, glm::dvec2& hi) const {
  lo = glm::dvec2(std::numeric_limits<double>::max());
  hi = glm::dvec2(std::numeric_limits<double>::lowest());
  if (terrain) {
    lo = glm::min(lo, glm::dvec2(terrain->height.origin()));
    hi = glm::max(hi, glm::dvec2(terrain->height.origin()) + terrain->height.sizeMetres());
  }
  for (const MeshGround* m : meshes) {
    lo = glm::min(lo, m->lo());
    hi = glm::max(hi, m->hi());
  }
  if (lo.x > hi.x) lo = hi = glm::dvec2(0.0);
}

Region2 Region2::disc(const glm::dvec2& c, double r) {
  Region2 g;
  g.kind = Kind::Disc;
  g.center = c;
  g.radius = r;
  return g;
}
Region2 Region2::rect(const glm::dvec2& lo, const glm::dvec2& hi) {
  Region2 g;
  g.kind = Kind::Rect;
  g.lo = glm::min(lo, hi);
  g.hi = glm::max(lo, hi);
  return g;
}
Region2 Region2::poly(std::vector<glm::dvec2> points) {
  Region2 g;
  g.kind = Kind::Polygon;
  g.polygon = std::move(points);
  return g;
}

bool Region2::contains(const glm::dvec2& p) const {
  switch (kind) {
    case Kind::Disc: {
      const glm::dvec2 d = p - center;
      return glm::dot(d, d) <= radius * radius;
    }
    case Kind::Rect: return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    case Kind::Polygon: {
      bool in = false;
      const size_t n = polygon.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const glm::dvec2 &a = polygon[i], &b = polygon[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
      }
      return in;
    }
  }
  return false;
}

void Region2::bounds(glm::dvec2& l, glm::dvec2& h) const {
  switch (kind) {
    case Kind::Disc:
      l = center - radius;
      h = center + radius;
      return;
    case Kind::Rect:
      l = lo;
      h = hi;
      return;
    case Kind::Polygon:
      l = glm::dvec2(std::numeric_limits<double>::max());
      h = glm::dvec2(std::numeric_limits<double>::lowest());
      for (const glm::dvec2& p : polygon) {
        l = glm::min(l, p);
        h = glm::max(h, p);
      }
      if (polygon.empty()) l = h = glm::dvec2(0.0);
      return;
  }
}

double Region2::boundsArea() const {
  glm::dvec2 l, h;
  bounds(l, h);
  return std::max(0.0, h.x - l.x) * std::max(0.0, h.y - l.y);
}

double Region2::area() const {
  switch (kind) {
    case Kind::Disc: return 3.14159265358979323846 * radius * radius;
    case Kind::Rect: return boundsArea();
    case Kind::Polygon: {
      double a = 0.0;
      const size_t n = polygon.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) a += (polygon[j].x + polygon[i].x) * (polygon[j].y - polygon[i].y);
      return std::abs(a) * 0.5;
    }
  }
  return 0.0;
}

}  // namespace hs::foliage
