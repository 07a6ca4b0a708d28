#pragma once
// Point and spot lights as the shaders read them (frame_blocks.h GpuLight,
// shaders/lights.glsl): camera-relative positions formed in double, the
// spot's cone as the scale and offset of a smooth step on cos(angle).
#include <glm/glm.hpp>

#include "render/frame_blocks.h"
#include "render/render_world.h"

namespace hs::render {

GpuLight gpuLight(const WorldLight& l, const glm::dvec3& origin);

}  // namespace hs::render
