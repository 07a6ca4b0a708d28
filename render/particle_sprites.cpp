#include "render/particle_sprites.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "particles/sprites.h"

namespace hs::render {
namespace {

// Layers: 0 snowflake, 1 smoke puff, 2 spark, 3.. the flame's frames.
constexpr int kSnowLayer = 0, kSmokeLayer = 1, kSparkLayer = 2, kFlameLayer = 3;
constexpr int kLayers = kFlameLayer + ParticleSprites::kFlameFrames;
// Fixed seeds: the sprites are part of the renderer, the same on every machine.
constexpr uint32_t kSpriteSeed = 36;

// A spark: white, alpha a smooth round falloff (a hot core, a soft rim).
std::vector<uint8_t> sparkDot(int size) {
  std::vector<uint8_t> px(size_t(size) * size * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double dx = (x + 0.5) / size * 2.0 - 1.0, dy = (y + 0.5) / size * 2.0 - 1.0;
      const double r = std::sqrt(dx * dx + dy * dy);
      const double a = std::clamp(1.0 - r, 0.0, 1.0);
      uint8_t* p = &px[(size_t(y) * size + x) * 4];
      p[0] = p[1] = p[2] = 255;
      p[3] = uint8_t(std::lround(255.0 * a * a));
    }
  return px;
}

}  // namespace

int ParticleSprites::layerBase(particles::Sprite s) {
  switch (s) {
    case particles::Sprite::Snowflake: return kSnowLayer;
    case particles::Sprite::Smoke: return kSmokeLayer;
    case particles::Sprite::Spark: return kSparkLayer;
    case particles::Sprite::Flame: return kFlameLayer;
  }
  return kSmokeLayer;
}

int ParticleSprites::layerCount(particles::Sprite s) { return s == particles::Sprite::Flame ? kFlameFrames : 1; }

GLuint ParticleSprites::texture() {
  if (made()) return texture_.id();
  texture_ = gl::createTexture(GL_TEXTURE_2D_ARRAY);
  const GLuint t = texture_.id();
  const int levels = int(std::log2(kSize)) + 1;
  glTextureStorage3D(t, levels, GL_SRGB8_ALPHA8, kSize, kSize, kLayers);
  auto layer = [&](int index, const uint8_t* rgba) {
    glTextureSubImage3D(t, 0, 0, 0, index, kSize, kSize, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  };
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  layer(kSnowLayer, particles::snowflakeSprite(kSize, kSpriteSeed).rgba8.data());
  layer(kSmokeLayer, particles::smokePuffSprite(kSize, kSpriteSeed).rgba8.data());
  layer(kSparkLayer, sparkDot(kSize).data());
  // The flipbook's atlas, row by row from the top left: one layer a frame.
  const particles::Flipbook flame = particles::flameFlipbook(kSize, kFlameFrames, kSpriteSeed);
  std::vector<uint8_t> frame(size_t(kSize) * kSize * 4);
  for (int f = 0; f < kFlameFrames; ++f) {
    const int cx = f % flame.columns, cy = f / flame.columns;
    for (int y = 0; y < kSize; ++y)
      std::memcpy(&frame[size_t(y) * kSize * 4],
                  &flame.atlas.rgba8[((size_t(cy) * kSize + y) * flame.atlas.width + size_t(cx) * kSize) * 4], size_t(kSize) * 4);
    layer(kFlameLayer + f, frame.data());
  }
  glGenerateTextureMipmap(t);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace hs::render
