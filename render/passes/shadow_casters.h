#pragma once
// How casters go into every shadow map (the sun's cascades, spot and point
// lights): the draw sources' Depth variant (draw_source.h) draws them, each
// source culling its casters once per shadow view; this is the state the
// shadow passes set around them. Include only inside render/.
#include <cstddef>

namespace hs::render {

// Slope-scaled and constant depth offset of the casters (glPolygonOffset,
// negative: away from the light, whose side has the larger depth in every
// shadow map). The normal offset of the receivers (shaders/shadows.glsl)
// does most of the work; this removes the acne left where light grazes.
constexpr float kCasterSlopeOffset = -2.0f;
constexpr float kCasterConstantOffset = -4.0f;

// Transient buffer sizes: powers of two from 256 bytes, so the pool reuses
// a buffer while the count of views or lights changes a little.
inline size_t shadowBufferBytes(size_t v) {
  size_t p = 256;
  while (p < v) p *= 2;
  return p;
}

}  // namespace hs::render
