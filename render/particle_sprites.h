#pragma once
// The particle sprites as one GL texture array (render/particle_source.h):
// particles/sprites.h's generated images (snowflake, smoke puff, the flame
// flipbook's frames) and a spark's soft round dot, each a layer of 64x64
// sRGB texels with mipmaps, made once on first use (no emitter: no
// texture). Include only inside render/.
#include <cstdint>

#include <epoxy/gl.h>

#include "particles/emitter.h"
#include "render/gl/gl_handle.h"

namespace hs::render {

class ParticleSprites {
 public:
  static constexpr int kSize = 64;          // texels across a layer
  static constexpr int kFlameFrames = 16;   // the flame flipbook's frames

  // The array, generated on the first call.
  GLuint texture();
  bool made() const { return texture_.id() != 0; }
  // The layers of a sprite: [base, base + count); a flipbook plays them in
  // order, a particle's frame modulo count.
  static int layerBase(particles::Sprite s);
  static int layerCount(particles::Sprite s);

 private:
  gl::Texture texture_;
};

}  // namespace hs::render
