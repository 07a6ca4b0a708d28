#pragma once
// Placing a camera in the render suites: the transform of an eye looking at
// a target, z up.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/transform.h"

namespace hs::test {

// Camera looks down local -Z with +Y up; build the basis from the direction.
inline scene::Transform lookFrom(glm::dvec3 eye, glm::dvec3 target) {
  const glm::dvec3 f = glm::normalize(target - eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
  const glm::dvec3 u = glm::cross(r, f);
  scene::Transform t;
  t.translation = eye;
  t.rotation = glm::quat_cast(glm::dmat3(r, u, -f));
  return t;
}

}  // namespace hs::test
