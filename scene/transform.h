#pragma once
// Double-precision local transform of an entity (DESIGN.md: world positions
// are doubles; the renderer forms camera-relative matrices from these).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace hs::scene {

struct Transform {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  glm::dvec3 scale{1.0};

  glm::dmat4 matrix() const;
  bool operator==(const Transform&) const = default;

  // Decomposes an affine matrix without shear (what matrix() produces).
  static Transform fromMatrix(const glm::dmat4& m);
};

// Euler angles in degrees, applied X then Y then Z about the parent's axes
// (Blender's default XYZ order), as the property panel shows them.
glm::dvec3 eulerDegrees(const glm::dquat& q);
glm::dquat fromEulerDegrees(const glm::dvec3& degrees);

}  // namespace hs::scene
