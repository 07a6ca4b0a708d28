#pragma once
// Sprite textures the presets need, generated on the CPU so no outside asset
// is needed (docs/particles.md, "Sprites"): a snowflake, a smoke puff and a
// flame flipbook. Each is a pure function of its size and seed (the same
// bytes on every machine: integer hashing and double arithmetic only), as
// 8-bit sRGB RGBA (core/image.h) with straight (not premultiplied) alpha.
#include <cstdint>

#include "core/image.h"

namespace hs::particles {

// A six-fold symmetric flake: a main arm with side branches whose places,
// lengths and angles come from the seed; white, alpha = coverage.
Image snowflakeSprite(int size, uint32_t seed);

// A soft round puff of fractal noise; white, alpha = density.
Image smokePuffSprite(int size, uint32_t seed);

// A flame flipbook: `frames` frames of frameSize^2 in an atlas of `columns`
// x `rows` (columns = ceil(sqrt(frames))), row by row from the top left.
// The noise scrolls upwards one period over the flipbook, so the last frame
// leads back into the first (it loops). Colour from deep red through orange
// and yellow to white with intensity; alpha = intensity.
struct Flipbook {
  Image atlas;
  int frames = 0, columns = 0, rows = 0, frameSize = 0;
};
Flipbook flameFlipbook(int frameSize, int frames, uint32_t seed);

}  // namespace hs::particles
