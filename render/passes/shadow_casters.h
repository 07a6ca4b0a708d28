#pragma once
// What casts shadows in a frame, for every shadow pass (the sun's cascades,
// spot and point lights): each mesh instance at the level of detail the
// views draw, with its bounding sphere and object data relative to the
// frame origin. Casters are not limited to the views' frusta: a tree behind
// the camera shadows the ground in front of it. Include only inside render/.
#include <vector>

#include <glm/glm.hpp>

#include "render/frame_blocks.h"
#include "render/frame_context.h"

namespace hs::render {

struct GpuMesh;

// Slope-scaled and constant depth offset of the casters (glPolygonOffset,
// negative: away from the light, whose side has the larger depth in every
// shadow map). The normal offset of the receivers (shaders/shadows.glsl)
// does most of the work; this removes the acne left where light grazes.
constexpr float kCasterSlopeOffset = -2.0f;
constexpr float kCasterConstantOffset = -4.0f;

// Transient buffer sizes: powers of two from 256 bytes, so the pool reuses
// a buffer while the caster count changes a little.
inline size_t shadowBufferBytes(size_t v) {
  size_t p = 256;
  while (p < v) p *= 2;
  return p;
}

// A submesh whose material has alpha cut-out (foliage cards): drawn with
// shaders/shadow_depth.frag's ALPHA_CUTOUT variant, which drops the
// fragments mesh.frag drops, so the shadow has the card's holes.
struct CutoutPart {
  uint32_t firstIndex = 0, indexCount = 0;
  GLuint texture = 0;     // base colour (its alpha); 0: none
  float opacity = 1.0f;   // the material's
  float threshold = 0.5f;
  bool translucent = false;  // opacity under 1, no cut-out: a stochastic share of the surface casts (shadow_depth.frag)
};

struct ShadowCaster {
  const GpuMesh* mesh = nullptr;
  glm::dvec3 centre{0.0};  // frame-relative
  double radius = 0.0;
  // Empty for an opaque mesh (one draw, the plain depth program: no cost
  // for cut-out where nothing cuts out). Otherwise its cut-out submeshes,
  // and its other submeshes as index ranges (first, count).
  std::vector<CutoutPart> cutouts;
  std::vector<std::pair<uint32_t, uint32_t>> opaqueRanges;
};

// One caster and one GpuObject (its draw's instance data) per mesh instance.
void gatherShadowCasters(const FrameContext& frame, std::vector<ShadowCaster>& casters,
                         std::vector<GpuObject>& objects);

// Draws casters[i] for each i of `which` into the bound depth target: the
// opaque ones with the plain depth program, the cut-out submeshes with the
// ALPHA_CUTOUT variant (built only when a caster has one). The instance
// index is i (the casters' object buffer is bound at kObjectBufferBinding).
void drawShadowCasters(RenderResources& resources, const std::vector<ShadowCaster>& casters,
                       const std::vector<uint32_t>& which);

}  // namespace hs::render
