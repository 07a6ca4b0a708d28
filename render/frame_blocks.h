#pragma once
// The C++ side of shaders/frame_blocks.glsl: the std140/std430 layouts of
// the frame's uniform and storage buffers and their binding points. Members
// match the GLSL declarations one for one (vec3 data travels in vec4 slots,
// as std140 pads it anyway). Include only inside render/.
#include <cmath>
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
  kFogBlockBinding = 8,          // uniform FogBlock (shaders/fog.glsl; only with fog on)
  // 9: buffer LightIndexList, 10: buffer LightCullStats (passes/light_culling.h)
  kLocalShadowBinding = 11,      // buffer LocalShadowBlock (spot/point shadows; only when one casts)
};

// Texture units: a material's textures, then the frame's shared maps.
enum TextureUnit : unsigned {
  kMaterialTextureUnit = 0,      // 0..7
  kShadowTextureUnit = 8,        // 8..11
  kEnvironmentTextureUnit = 12,  // 12..15
  kLocalShadowTextureUnit = 16,  // 16..19: spot and point light shadow maps
};

struct FrameBlock {
  glm::vec4 sunDir{0.0f, 0.0f, 1.0f, 0.0f};  // xyz towards the sun (world), w: has sun
  glm::vec4 sunColor{0.0f};
  glm::vec4 skyZenith{0.0f};
  glm::vec4 skyHorizon{0.0f};
  glm::vec4 groundColor{0.0f};
  glm::vec4 params{0.0f};  // ambient, exposure multiplier (light_units.h), light count, unused
  // Sky and environment: x = 1 when EnvironmentBlock and its cube are live.
  glm::vec4 environment{0.0f};
  // The frame's time (scene::SceneTime): x: seconds from the sequence's
  // start, y: frame number, z: fract(seconds) taken in double (periodic
  // effects keep full precision late in a long shot), w: 1 / fps.
  glm::vec4 time{0.0f};
};
static_assert(sizeof(FrameBlock) == 8 * 16);

// FrameBlock.time of a scene time.
inline glm::vec4 frameTimeOf(double seconds, int64_t frame, double fps) {
  return glm::vec4(float(seconds), float(frame), float(seconds - std::floor(seconds)),
                   fps > 0.0 ? float(1.0 / fps) : 0.0f);
}

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

// A point or spot light (lights: shaders/lights.glsl).
struct GpuLight {
  glm::vec4 position{0.0f};   // xyz relative to the frame origin, w: range (m)
  glm::vec4 color{0.0f};      // rgb: candela in scene units, w: type (1 point, 2 spot)
  glm::vec4 direction{0.0f};  // xyz: the way a spot shines (unit), w: unused
  glm::vec4 spot{0.0f};       // x: 1 / (cos inner − cos outer), y: −cos outer · x (half angles);
                              // z, w: reserved for shadows (shadows.glsl)
};
static_assert(sizeof(GpuLight) == 4 * 16);

struct GpuObject {
  glm::mat4 model{1.0f};         // relative to the frame origin
  glm::mat4 normalMatrix{1.0f};  // mat3 in the upper left
  glm::vec4 tint{1.0f};
};
static_assert(sizeof(GpuObject) == 2 * 64 + 16);

// Shadows (shaders/shadows.glsl, render/passes/shadow_passes.h): the sun's
// cascades, relative to the frame origin, shared by every view of a frame.
struct ShadowBlock {
  glm::mat4 sunCascade[4]{};  // frame-relative position -> map (u, v, depth)
  glm::vec4 sunTexelMetres{0.0f};  // world size of a texel, per cascade
  glm::vec4 sunParams{0.0f};  // x: cascade count (0: no sun shadow), y: PCF radius, z: 1 / map size
  // Spot and point lights: x: entries in LocalShadowBlock (0: none, the
  // buffer is not bound), y: 1 / the maps' layer size, z: PCF radius.
  glm::vec4 localParams{0.0f};
};
static_assert(sizeof(ShadowBlock) == 4 * 64 + 3 * 16);

// One per point or spot light of the frame (binding 11, std430; indexed
// like the light buffer): the faces' matrices into their maps and where the
// maps are. A light without a map has params.x = -1.
struct GpuLocalShadow {
  glm::mat4 faces[6]{};  // frame-relative position -> clip of the face's map, bias applied (divide by w)
  glm::vec4 params{-1.0f, 0.0f, 0.0f, 0.0f};  // x: first layer (-1: none), y: faces (1 or 6),
                                              // z: texel size at 1 m, w: the light's share of the layer
};
static_assert(sizeof(GpuLocalShadow) == 6 * 64 + 16);

}  // namespace hs::render
