#include "render/terrain_lod.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs::render {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Box {
  glm::dvec3 min, max;  // terrain-local metres
};

class Selector {
 public:
  Selector(const LodInput& in, LodSelection& out) : in_(in), out_(out) {}

  void run() {
    const terrain::MinMaxTree& t = *in_.tree;
    out_.levels = std::min(t.levels(), kTerrainMaxLevels);
    computeRanges();
    const int top = out_.levels - 1;
    for (int ny = 0; ny < t.nodesY(top); ++ny)
      for (int nx = 0; nx < t.nodesX(top); ++nx) visit(top, nx, ny);
  }

 private:
  int cells(int level) const { return kTerrainGridQuads << level; }

  Box box(int level, int nx, int ny) const {
    const int c = cells(level);
    const int x0 = nx * c, y0 = ny * c;
    const int x1 = std::min(x0 + c, in_.samplesX - 1), y1 = std::min(y0 + c, in_.samplesY - 1);
    const terrain::HeightRange r = in_.tree->node(level, nx, ny);
    return {{x0 * in_.spacing.x, y0 * in_.spacing.y, double(r.min)}, {x1 * in_.spacing.x, y1 * in_.spacing.y, double(r.max)}};
  }

  bool inFrustum(const Box& b) const {
    if (!in_.frustum) return true;
    for (const glm::dvec4& p : in_.frustum->planes) {
      const glm::dvec3 n(p);
      // The corner furthest along the plane's normal.
      const glm::dvec3 v(n.x >= 0 ? b.max.x : b.min.x, n.y >= 0 ? b.max.y : b.min.y, n.z >= 0 ? b.max.z : b.min.z);
      if (glm::dot(n, v + in_.originRelative) + p.w < 0.0) return false;
    }
    return true;
  }

  double distance(const Box& b) const {
    const glm::dvec3 c = glm::clamp(in_.cameraLocal, b.min, b.max);
    return glm::length(c - in_.cameraLocal);
  }

  bool exists(int level, int nx, int ny) const {
    return nx < in_.tree->nodesX(level) && ny < in_.tree->nodesY(level);
  }

  void emit(int level, int x0, int y0) {
    if (x0 >= in_.samplesX - 1 || y0 >= in_.samplesY - 1) return;
    out_.patches.push_back({x0, y0, 1 << level, level});
  }

  // The four quadrants of node (level, nx, ny), drawn at `level`.
  void emitNode(int level, int nx, int ny) {
    const int c = cells(level), h = c / 2;
    for (int q = 0; q < 4; ++q) emit(level, nx * c + (q & 1) * h, ny * c + (q >> 1) * h);
  }

  void visit(int level, int nx, int ny) {
    ++out_.nodesVisited;
    const Box b = box(level, nx, ny);
    if (!inFrustum(b)) {
      ++out_.nodesCulled;
      return;
    }
    if (level == 0) {
      emitNode(0, nx, ny);
      return;
    }
    const double finer = out_.range[size_t(level - 1)];
    if (distance(b) >= finer) {
      emitNode(level, nx, ny);
      return;
    }
    const int c = cells(level), h = c / 2;
    for (int q = 0; q < 4; ++q) {
      const int cx = 2 * nx + (q & 1), cy = 2 * ny + (q >> 1);
      if (!exists(level - 1, cx, cy)) continue;  // beyond the terrain
      const Box cb = box(level - 1, cx, cy);
      if (distance(cb) < finer) {
        visit(level - 1, cx, cy);
      } else if (inFrustum(cb)) {
        emit(level, nx * c + (q & 1) * h, ny * c + (q >> 1) * h);
      } else {
        ++out_.nodesCulled;
      }
    }
  }

  void computeRanges() {
    const int levels = out_.levels;
    const double m = kTerrainMorphFraction;
    const double spacing = std::max(in_.spacing.x, in_.spacing.y);
    for (int l = 0; l < kTerrainMaxLevels; ++l) {
      out_.range[size_t(l)] = kInfinity;
      out_.morphStart[size_t(l)] = kInfinity;
    }
    if (in_.errorPixels <= 0.0) return;  // full resolution: every node subdivides
    double prevRange = 0.0, prevDiag = 0.0;
    for (int l = 0; l + 1 < levels; ++l) {
      const double needError = double(in_.error->error(l + 1)) * in_.pixelsPerUnit / in_.errorPixels / (1.0 - m);
      const double needCrack = l > 0 ? (prevRange + prevDiag) / (1.0 - m) : 0.0;
      // At least one node diagonal, so the morph zone is never degenerate.
      const double diag = nodeDiagonal(l, spacing);
      const double r = std::max({needError, needCrack, diag});
      out_.range[size_t(l)] = r;
      out_.morphStart[size_t(l)] = r * (1.0 - m);
      prevRange = r;
      prevDiag = diag;
    }
  }

  // 3D diagonal of the largest level-`l` node: horizontal extent and the
  // largest height range among the level's nodes.
  double nodeDiagonal(int l, double spacing) const {
    float range = 0.0f;
    for (int y = 0; y < in_.tree->nodesY(l); ++y)
      for (int x = 0; x < in_.tree->nodesX(l); ++x) {
        const terrain::HeightRange r = in_.tree->node(l, x, y);
        range = std::max(range, r.max - r.min);
      }
    const double side = double(cells(l)) * spacing;
    return std::sqrt(2.0 * side * side + double(range) * double(range));
  }

  const LodInput& in_;
  LodSelection& out_;
};

}  // namespace

double lodPixelsPerUnit(const RenderView& view) {
  // Centre: pixels per unit of offset/depth. At a ray making angle theta with
  // the view axis, a perpendicular offset at Euclidean distance d is at
  // depth d cos(theta): the worst case is the view's corner.
  const double t = std::tan(view.fovY * 0.5);
  const double k = double(view.height) / (2.0 * t);
  const double corner = std::atan(std::sqrt(t * t * (1.0 + view.aspect() * view.aspect())));
  return k / std::cos(corner);
}

LodSelection selectLod(const LodInput& in) {
  LodSelection out;
  if (!in.tree || !in.error || in.tree->levels() == 0) return out;
  Selector(in, out).run();
  return out;
}

float fullMeshHeightAt(const terrain::Heightfield& hf, const glm::dvec2& p) {
  const int cx = std::clamp(int(std::floor(p.x)), 0, hf.samplesX() - 2);
  const int cy = std::clamp(int(std::floor(p.y)), 0, hf.samplesY() - 2);
  const float fx = float(std::clamp(p.x - cx, 0.0, 1.0)), fy = float(std::clamp(p.y - cy, 0.0, 1.0));
  const float h00 = hf.at(cx, cy), h10 = hf.at(cx + 1, cy), h01 = hf.at(cx, cy + 1), h11 = hf.at(cx + 1, cy + 1);
  return fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);
}

}  // namespace hs::render
