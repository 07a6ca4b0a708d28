#pragma once
// Mip chains for alpha cut-out textures that keep, at every level, the
// share of texels the cut-out keeps at level 0 (Castaño 2010, "Computing
// alpha mipmaps"; what Unreal's and Unity's "preserve alpha coverage" mip
// settings do). A plain 2x2 box filter averages a leaf's edge with the
// gaps around it: a few levels down most texels fall under the threshold,
// and far trees lose their leaves (the generated conifer's needles, 24 %
// cover, keep none four levels down: test_alpha_mips). Here each level is the box filter of
// the one above (colour weighted by alpha, so the transparent texels'
// colour does not darken the leaves' edges; in linear light), and its alpha
// is then scaled by the factor that makes as many of its bilinearly
// filtered samples pass `threshold` as level 0 has texels that do, in
// proportion (samples, not texels: a needle one texel wide passes as a
// texel, but the filter averages it with the gaps beside it). Written
// here: no library the project uses builds such chains. Plain C++, no GL.
#include <cstdint>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::mesh {

struct MipLevel {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // sRGB colour, straight alpha (as Texture::rgba)
};

// The share of texels whose alpha (0..255) is at least threshold x 255.
double alphaCoverage(const std::vector<uint8_t>& rgba, float threshold);
// The same over where a bilinear sampler reads the level: four samples a
// texel, a quarter texel off its centre each way (wrapping).
double filteredAlphaCoverage(const MipLevel& level, float threshold);

// Levels 1 .. the 1x1 level of `level0` (RGBA8, sRGB), each half the size
// of the one above (rounded down, at least 1), as GL counts them.
// `threshold` in (0, 1): the cut-out's; outside it, no alpha scaling (the
// box filter alone, colour weighted by alpha all the same).
std::vector<MipLevel> coveragePreservingMips(const Texture& level0, float threshold);

// The plain box-filtered chain (no weighting, no scaling): what GL's
// glGenerateMipmap makes, for comparison in tests and benchmarks.
std::vector<MipLevel> boxFilteredMips(const Texture& level0);

}  // namespace hs::mesh
