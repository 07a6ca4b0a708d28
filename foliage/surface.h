#pragma once
// What foliage stands on: a terrain (its drawn surface: two triangles per
// cell split along (i, j)-(i+1, j+1), as terrain/heightfield.h draws and
// ray_pick.h picks, so an instance's base lies on what the viewport shows)
// and mesh surfaces (scans: triangles binned in XY for region queries, and
// meshproc's ClosestPointBvh for snapping a point onto the surface).
// Slopes are those of the triangle under the point: exact for planes, so
// filters can be tested at their limits.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "foliage/instance.h"
#include "mesh/mesh_data.h"
#include "meshproc/closest_point_bvh.h"
#include "terrain/terrain.h"

namespace hs::foliage {

struct SurfacePoint {
  glm::dvec3 position{0.0};     // world
  glm::dvec3 normal{0, 0, 1};   // unit, world
  double slopeDeg = 0.0;        // angle of the normal from +Z: 0 flat, 90 vertical
  Surface surface = Surface::Terrain;
};

// Slope in degrees of a surface with this (not necessarily unit) normal;
// exactly 0 for a normal along +Z and exactly 90 for a horizontal one.
double slopeDegrees(const glm::dvec3& normal);

// The drawn terrain surface at a world XY: nullopt outside the grid or
// over a hole.
std::optional<SurfacePoint> terrainSurface(const terrain::Heightfield& hf, const glm::dvec2& world);
// A paint layer's weight at a world XY, interpolated on the same
// triangles (so equal corner weights give that weight exactly).
double terrainLayerWeight(const terrain::Terrain& t, int layer, const glm::dvec2& world);
// The paint layer whose material is called `name`; -1 if none.
int terrainLayerIndex(const terrain::Terrain& t, const std::string& name);

// A mesh placed at its origin (MeshData::origin is its world position).
class MeshGround {
 public:
  explicit MeshGround(const mesh::MeshData& mesh);
  const mesh::MeshData& mesh() const { return *mesh_; }
  size_t triangleCount() const { return mesh_->triangleCount(); }
  // Triangles whose XY bounds meet the world rectangle [lo, hi] (each once).
  void trianglesIn(const glm::dvec2& lo, const glm::dvec2& hi, std::vector<uint32_t>& out) const;
  double area(uint32_t face) const { return area_[face]; }
  // The point with barycentric coordinates `bary` on `face`, in world.
  SurfacePoint pointOn(uint32_t face, const glm::dvec3& bary) const;
  // The nearest surface point to a world position (within maxDistance).
  std::optional<SurfacePoint> closest(const glm::dvec3& world, double maxDistance) const;
  // Is there a triangle of this mesh above `world` within `height` (a
  // point inside the scan's footprint, or under a ledge)? Any hit will do.
  bool covers(const glm::dvec3& world, double height) const;
  // The first surface point along a ray from `origin` (world) in the unit
  // `direction`, within maxDistance (an editor brush's pick on a scan):
  // found to within 1 mm by halving the interval where any triangle is
  // crossed, so it needs no nearest-hit walk of its own.
  std::optional<SurfacePoint> raycast(const glm::dvec3& origin, const glm::dvec3& direction,
                                      double maxDistance) const;
  glm::dvec2 lo() const { return lo_; }
  glm::dvec2 hi() const { return hi_; }

 private:
  const mesh::MeshData* mesh_;
  mesh::ClosestPointBvh bvh_;
  std::vector<double> area_;
  std::vector<glm::dvec3> faceNormal_;  // unit (zero for degenerate faces)
  glm::dvec2 lo_{0.0}, hi_{0.0};        // world XY bounds
  double bin_ = 1.0;
  int binsX_ = 1, binsY_ = 1;
  std::vector<uint32_t> binStart_, binFaces_;  // CSR: faces of each bin
};

// The surfaces of a scene that foliage may stand on (not owned).
struct Ground {
  const terrain::Terrain* terrain = nullptr;
  std::vector<const MeshGround*> meshes;
  // Terrain points with a mesh above them within this height take no
  // foliage: a forest on the valley floor does not grow inside a scanned
  // pillar standing on it, nor right under its ledges. 0: off.
  double coverHeight = 100.0;
  // World XY bounds of everything (the whole-scene scatter's area).
  void bounds(glm::dvec2& lo, glm::dvec2& hi) const;
};

// A region of the XY plane: a disc (a brush dab), a rectangle or a
// polygon (a lasso, a fill area). Inclusive on its boundary.
struct Region2 {
  enum class Kind { Disc, Rect, Polygon } kind = Kind::Rect;
  glm::dvec2 center{0.0};
  double radius = 0.0;
  glm::dvec2 lo{0.0}, hi{0.0};
  std::vector<glm::dvec2> polygon;

  static Region2 disc(const glm::dvec2& c, double r);
  static Region2 rect(const glm::dvec2& lo, const glm::dvec2& hi);
  static Region2 poly(std::vector<glm::dvec2> points);
  bool contains(const glm::dvec2& p) const;
  void bounds(glm::dvec2& l, glm::dvec2& h) const;
  double boundsArea() const;
  double area() const;  // of the region itself (a polygon's by the shoelace formula)
};

}  // namespace hs::foliage
