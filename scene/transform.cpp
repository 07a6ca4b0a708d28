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
  // R = Rz * Ry * Rx; read the angles back from the rotation matrix.
  const glm::dmat3 m = glm::mat3_cast(q);
  const double sy = -m[0][2];  // -R[2][0] in row-major terms
  double x, y, z;
  if (std::abs(sy) < 0.9999999) {
    y = std::asin(sy);
    x = std::atan2(m[1][2], m[2][2]);
    z = std::atan2(m[0][1], m[0][0]);
  } else {  // gimbal lock: fold Z into X
    y = sy > 0 ? M_PI / 2 : -M_PI / 2;
    x = std::atan2(-m[2][1], m[1][1]);
    z = 0.0;
  }
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
