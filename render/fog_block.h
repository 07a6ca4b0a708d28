#pragma once
// Fog on the GPU (shaders/fog.glsl): the uniform block and the shader
// variant a frame's fog mode needs. With fog off there is neither: no
// define, so fog.glsl compiles to nothing, and no buffer is bound.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene_state.h"

namespace hs::render {

// std140, binding kFogBlockBinding (frame_blocks.h).
struct FogBlock {
  glm::vec4 colour{0.0f};  // rgb: fog colour (scene units)
  glm::vec4 params{0.0f};  // x: k1, y: k2 (depth cue); z: density, w: height falloff (height fog)
  glm::vec4 height{0.0f};  // x: fog height relative to the frame origin (m)
};
static_assert(sizeof(FogBlock) == 3 * 16);

// "FOG_DEPTH_CUE" or "FOG_HEIGHT", none with fog off.
std::vector<std::string> fogDefines(const scene::SceneSettings& s);
// `originZ`: the frame origin's world height (heights reach the GPU relative to it).
FogBlock fogBlock(const scene::SceneSettings& s, double originZ);

}  // namespace hs::render
