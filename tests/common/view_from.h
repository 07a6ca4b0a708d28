#pragma once
// A render suite's camera in one line: `width` x `height` pixels, vertical
// field of view `fovYDegrees`, at `eye` looking at `target` (look_from.h).
#include "look_from.h"
#include "render/render_view.h"

namespace hs::test {

inline render::RenderView viewFrom(glm::dvec3 eye, glm::dvec3 target, int width, int height, double fovYDegrees) {
  render::RenderView v;
  v.width = width;
  v.height = height;
  v.fovY = glm::radians(fovYDegrees);
  v.eye = eye;
  v.orientation = lookFrom(eye, target).rotation;
  return v;
}

}  // namespace hs::test
