#pragma once
// The C++ side of shaders/material_block.glsl: one material as the
// MaterialBlock storage buffer (binding 4, kMaterialBufferBinding) holds
// it, std430, member for member. Include only inside render/.
#include <cstdint>

#include <glm/glm.hpp>

namespace hs::render {

enum MaterialFlag : uint32_t {
  kMatBaseTexture = 1u,
  kMatNormalMap = 2u,
  kMatHeightMap = 4u,
  kMatAlphaCutout = 8u,
  kMatTwoSided = 16u,
  kMatUnlit = 32u,
};

struct GpuMaterial {
  glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f};  // rgb linear, a: opacity
  glm::vec4 emission{0.0f, 0.0f, 0.0f, 0.5f};   // rgb: colour x strength, a: cut-out threshold
  glm::vec4 surface{0.5f, 0.0f, 0.5f, 32.0f};   // roughness, metallic, specular, shininess
  glm::vec4 detail{1.0f, 0.0f, 0.0f, 0.0f};     // normal strength, height scale (m), transmission, unused
  glm::uvec4 kind{0u, kMatTwoSided, 0u, 0u};    // x: lighting model, y: MaterialFlag bits
};
static_assert(sizeof(GpuMaterial) == 5 * 16);

}  // namespace hs::render
