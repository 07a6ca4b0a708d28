#pragma once
// The C++ side of shaders/frame_blocks.glsl: the std140/std430 layouts of
// the frame's uniform and storage buffers and their binding points. Members
// match the GLSL declarations one for one (vec3 data travels in vec4 slots,
// as std140 pads it anyway). Include only inside render/.
#include <cstdint>

#include <glm/glm.hpp>

namespace hs::render {

enum Binding : unsigned {
  kFrameBlockBinding = 0,        // uniform FrameBlock
  kViewBlockBinding = 1,         // uniform ViewBlock
  kLightBufferBinding = 2,       // buffer LightBlock
  kObjectBufferBinding = 3,      // buffer ObjectBlock
  kMaterialBufferBinding = 4,    // buffer MaterialBlock
  kShadowBlockBinding = 5,       // uniform ShadowBlock
  kEnvironmentBlockBinding = 6,  // uniform EnvironmentBlock
  kLightGridBinding = 7,         // buffer LightGrid (clustered light lists)
};

// Texture units: a material's textures, then the frame's shared maps.
enum TextureUnit : unsigned {
  kMaterialTextureUnit = 0,      // 0..7
  kShadowTextureUnit = 8,        // 8..11
  kEnvironmentTextureUnit = 12,  // 12..15
};

struct FrameBlock {
  glm::vec4 sunDir{0.0f, 0.0f, 1.0f, 0.0f};  // xyz towards the sun (world), w: has sun
  glm::vec4 sunColor{0.0f};
  glm::vec4 skyZenith{0.0f};
  glm::vec4 skyHorizon{0.0f};
  glm::vec4 groundColor{0.0f};
  glm::vec4 params{0.0f};  // ambient, exposure, light count, unused
  // Sky and environment: x = 1 when EnvironmentBlock and its cube are live.
  glm::vec4 environment{0.0f};
};
static_assert(sizeof(FrameBlock) == 7 * 16);

// Binding 6 (shaders/environment.glsl), written by the environment pass:
// sh by shaders/env_sh.comp, params by the CPU.
struct EnvironmentBlock {
  glm::vec4 sh[9];     // rgb: E(n)/pi coefficients
  glm::vec4 params{0.0f};  // x: the specular cube's last mip level
};
static_assert(sizeof(EnvironmentBlock) == 10 * 16);

struct ViewBlock {
  glm::mat4 projection{1.0f};
  glm::mat4 viewRotation{1.0f};
  glm::mat4 invViewRotation{1.0f};
  glm::vec4 eyeOffset{0.0f};
  glm::vec4 viewport{0.0f};
  glm::vec4 tanHalfFov{0.0f};
};
static_assert(sizeof(ViewBlock) == 3 * 64 + 3 * 16);

struct GpuLight {
  glm::vec4 position{0.0f};  // xyz relative to the frame origin, w: range
  glm::vec4 color{0.0f};
};

struct GpuObject {
  glm::mat4 model{1.0f};         // relative to the frame origin
  glm::mat4 normalMatrix{1.0f};  // mat3 in the upper left
  glm::vec4 tint{1.0f};
};
static_assert(sizeof(GpuObject) == 2 * 64 + 16);

}  // namespace hs::render
