#include "scene/transform.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace hs::scene {

glm::dmat4 Transform::matrix() const {
  glm::dmat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::dvec4(translation, 1.0);
  return m;
}

Transform Transform::fromMatrix(const glm::dmat4& m) {
  Transform t;
  t.translation = glm::dvec3(m[3]);
  glm::dvec3 c0(m[0]), c1(m[1]), c2(m[2]);
  t.scale = {glm::length(c0), glm::length(c1), glm::length(c2)};
  // A mirrored basis keeps its handedness in the sign of one scale axis.
  if (glm::dot(glm::cross(c0, c1), c2) < 0.0) t.scale.x = -t.scale.x;
  glm::dmat3 r(t.scale.x != 0.0 ? c0 / t.scale.x : glm::dvec3(1, 0, 0),
               t.scale.y != 0.0 ? c1 / t.scale.y : glm::dvec3(0, 1, 0),
               t.scale.z != 0.0 ? c2 / t.scale.z : glm::dvec3(0, 0, 1));
  t.rotation = glm::normalize(glm::quat_cast(r));
  return t;
}

glm::dvec3 eulerDegrees(const glm::dquat& q) {
  // R = Rz * Ry * Rx (m[column][row]). Z comes first, from R's first column
  // (0 in gimbal lock, where Z folds into X); X and Y then come from
  // Rz^T * R = Ry * Rx, whose second row (0, cos x, -sin x) does not shrink
  // as Y nears +-90 degrees, so the angles describe R exactly however close
  // to the lock it is. (Snapping to the lock from 0.026 degrees away turned
  // such rotations by up to that much.)
  const glm::dmat3 m = glm::mat3_cast(q);
  const double cosY = std::hypot(m[0][0], m[0][1]);
  const double z = cosY > 1e-9 ? std::atan2(m[0][1], m[0][0]) : 0.0;
  const double cz = std::cos(z), sz = std::sin(z);
  const double x = std::atan2(sz * m[2][0] - cz * m[2][1], cz * m[1][1] - sz * m[1][0]);
  const double y = std::atan2(-m[0][2], cz * m[0][0] + sz * m[0][1]);
  return glm::degrees(glm::dvec3(x, y, z));
}

glm::dquat fromEulerDegrees(const glm::dvec3& degrees) {
  const glm::dvec3 r = glm::radians(degrees);
  const glm::dquat qx = glm::angleAxis(r.x, glm::dvec3(1, 0, 0));
  const glm::dquat qy = glm::angleAxis(r.y, glm::dvec3(0, 1, 0));
  const glm::dquat qz = glm::angleAxis(r.z, glm::dvec3(0, 0, 1));
  return glm::normalize(qz * qy * qx);
}

}  // namespace hs::scene
