#pragma once
// Textures made in code: height maps for parallax occlusion mapping and the
// normal maps derived from them (the demo's detail materials, the tests of
// normal and parallax mapping). No data files, nothing to attribute.
#include <cstdint>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// Bricks in running bond: `rows` courses of `columns` bricks across a
// square `size` x `size` image that tiles; brick faces are white (high),
// mortar black, with a bevel `bevel` of a brick's height wide. Grey RGBA8,
// linear (a height map is not a colour).
Texture brickHeightMap(int size, int rows, int columns, float bevel = 0.12f);

// Smooth value noise in octaves, tiling, 0..1 (rock-like relief).
Texture noiseHeightMap(int size, int octaves, uint32_t seed);

// Stones: a tiling cellular pattern (`cells` x `cells` jittered stones),
// each stone a rounded dome (white top) with dark crevices between them,
// roughened by value noise.
Texture stoneHeightMap(int size, int cells, uint32_t seed);

// The tangent-space normal map of a height map (OpenGL convention: red
// +u, green the image's up, blue out of the surface), by central
// differences with wrap-around. `relief` is the height of white over the
// width of the whole image (0.02: 2% of the tile's width).
Texture normalMapFromHeight(const Texture& height, float relief);

// A colour texture: `dark` where the height map is black, `light` where it
// is white (linear RGB), encoded sRGB.
Texture tintByHeight(const Texture& height, glm::vec3 dark, glm::vec3 light);

}  // namespace hs::mesh
