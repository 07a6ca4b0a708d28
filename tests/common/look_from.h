#pragma once
// Placing a camera in the render suites: the transform of an eye looking at
// a target, z up.
#include <glm/glm.hpp>

#include "scene/transform.h"
#include "sequencer/camera_path.h"

namespace hs::test {

// Cameras look down local -Z with +Y up (sequencer::lookRotation).
inline scene::Transform lookFrom(glm::dvec3 eye, glm::dvec3 target) {
  scene::Transform t;
  t.translation = eye;
  t.rotation = sequencer::lookRotation(target - eye);
  return t;
}

}  // namespace hs::test
