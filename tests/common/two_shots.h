#pragma once
// Views for the tests of several cameras in one frame (test_view_groups,
// test_transitions, test_stylised): an eye of a pair, and the demo's second
// shot from across the valley.
#include <glm/gtc/quaternion.hpp>

#include "render/render_view.h"

namespace hs::test {

// An eye offset sideways by `metres` (a stereo pair without its rig's toe-in).
inline render::RenderView shiftedSideways(render::RenderView v, double metres) {
  v.eye += glm::dvec3(glm::transpose(v.viewRotation())[0]) * metres;
  return v;
}

// The second shot of `first` (a demo camera's view): from the other side of
// the valley, looking back.
inline render::RenderView otherSideOfTheValley(const render::RenderView& first) {
  render::RenderView v = first;
  v.eye += glm::dvec3(60.0, 40.0, 15.0);
  v.orientation = glm::angleAxis(glm::radians(150.0), glm::dvec3(0, 0, 1)) * first.orientation;
  return v;
}

}  // namespace hs::test
