#pragma once
// What particles collide with (docs/particles.md, "Collision"). A collider
// answers one question: the first point where the segment from -> to (world
// coordinates, double) meets its surface, with the surface normal there.
// The evaluator refines the hit time on the particle's exact trajectory
// against the tangent plane of that point, so no particle ends below a
// surface by more than the collider's own tolerance (1e-6 m for the height
// field below).
//
// Two colliders come with the library: a height field z = h(x, y) given as a
// function (a terrain, a ground plane), and a triangle mesh (brute force, for
// small meshes and tests); anything else (a scene's BVH) implements
// Collider or wraps its ray cast in RaycastCollider.
#include <functional>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

namespace hs::particles {

struct Hit {
  double fraction = 0.0;  // along from -> to, in [0, 1]
  glm::dvec3 point{0.0};  // world
  glm::dvec3 normal{0.0, 0.0, 1.0};  // unit, facing the side `from` is on
};

class Collider {
 public:
  virtual ~Collider() = default;
  virtual std::optional<Hit> raycast(const glm::dvec3& from, const glm::dvec3& to) const = 0;
};

// z = height(x, y). `normal` may be empty: then the normal comes from central
// differences of the height over `spacing`. The segment is sampled every
// `spacing` metres horizontally (features narrower than that can be
// missed), the first sign change of z - h is bisected to 1e-6 m.
// A segment starting below the surface hits at its start, at the surface.
class HeightFieldCollider : public Collider {
 public:
  HeightFieldCollider(std::function<double(double, double)> height,
                      std::function<glm::dvec3(double, double)> normal = {}, double spacing = 0.25);
  std::optional<Hit> raycast(const glm::dvec3& from, const glm::dvec3& to) const override;
  double height(double x, double y) const { return height_(x, y); }
  glm::dvec3 normal(double x, double y) const;
  double spacing() const { return spacing_; }  // between the segment's samples, metres

 private:
  std::function<double(double, double)> height_;
  std::function<glm::dvec3(double, double)> normal_;
  double spacing_;
};

// Triangles (world coordinates), two-sided, tested one by one (Moller-Trumbore).
class TriangleMeshCollider : public Collider {
 public:
  explicit TriangleMeshCollider(std::vector<glm::dvec3> corners);  // 3 per triangle
  std::optional<Hit> raycast(const glm::dvec3& from, const glm::dvec3& to) const override;

 private:
  std::vector<glm::dvec3> corners_;
};

// A ray cast someone else implements (the scene's mesh BVH, the terrain's
// own ray pick), as a callback.
class RaycastCollider : public Collider {
 public:
  using Fn = std::function<std::optional<Hit>(const glm::dvec3&, const glm::dvec3&)>;
  explicit RaycastCollider(Fn fn) : fn_(std::move(fn)) {}
  std::optional<Hit> raycast(const glm::dvec3& from, const glm::dvec3& to) const override { return fn_(from, to); }

 private:
  Fn fn_;
};

// The nearest hit among several colliders.
std::optional<Hit> nearestHit(const std::vector<const Collider*>& colliders, const glm::dvec3& from,
                              const glm::dvec3& to);

}  // namespace hs::particles
