#pragma once
// CDLOD node selection (Strugar 2009, "Continuous Distance-Dependent Level
// of Detail"), on the CPU and without GL so tests and benchmarks can run it.
//
// The terrain is drawn with one grid mesh of G/2 x G/2 quads (a node
// quadrant), instanced: a quadrant of level L spans G/2 * 2^L samples with
// every 2^L-th sample as a vertex. Each level L is used within a distance
// range; over the last part of the range its vertices morph (odd grid
// vertices slide onto their even neighbours) so that at the range's end the
// mesh is exactly level L+1's: no popping, and no cracks, because a level-L
// quadrant only ever borders level L+1 where its vertices have fully morphed
// (the ranges are built so that this holds, below).
//
// Ranges come from the error bound instead of fixed ratios: level L+1's
// geometric error e_{L+1} (terrain::LodErrorMap: the largest vertical
// distance between that level's mesh and the full-resolution mesh) appears
// on screen as at most e * K / d pixels at distance d, with K the pixels per
// unit of view-plane offset at the edge of the view (the centre's K divided
// by the cosine of the corner's angle). So level L may start morphing into
// L+1 where e_{L+1} K / d <= tau:
//     morphStart_L = r_L (1 - m) >= e_{L+1} K / tau
// and, for the crack-free rule (a quadrant of level L+1 next to a level-L
// quadrant has not started morphing), with D_L the 3D diagonal of a level-L
// node:
//     morphStart_{L+1} >= r_L + D_L
// r_L is the smallest value meeting both; the top level never morphs.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"
#include "terrain/lod_error.h"
#include "terrain/minmax_tree.h"

namespace hs::render {

constexpr int kTerrainGridQuads = 32;   // G: quads per node side (leaf node = 32 cells)
constexpr int kTerrainMaxLevels = 16;
constexpr double kTerrainMorphFraction = 0.3;

// One quadrant to draw: (G/2)^2 quads of `scale` samples from sample (x0, y0).
struct LodPatch {
  int x0 = 0, y0 = 0;
  int scale = 1;   // 2^level
  int level = 0;
};

struct LodInput {
  const terrain::MinMaxTree* tree = nullptr;  // built with leafCells = kTerrainGridQuads
  const terrain::LodErrorMap* error = nullptr;
  glm::dvec2 spacing{1.0};
  int samplesX = 0, samplesY = 0;
  glm::dvec3 cameraLocal{0.0};    // camera relative to the terrain origin, metres
  glm::dvec3 originRelative{0.0}; // terrain origin minus the eye (camera-relative world), for culling
  const Frustum* frustum = nullptr;
  double pixelsPerUnit = 1000.0;  // K: screen pixels per unit of (offset / depth), worst case over the view
  double errorPixels = 1.0;       // tau; <= 0 selects the full resolution everywhere
};

struct LodSelection {
  std::vector<LodPatch> patches;
  int levels = 0;
  std::array<double, kTerrainMaxLevels> range{};       // r_L, metres (top level: infinite)
  std::array<double, kTerrainMaxLevels> morphStart{};  // metres
  size_t nodesVisited = 0, nodesCulled = 0;
  size_t triangles() const { return patches.size() * size_t(kTerrainGridQuads / 2) * size_t(kTerrainGridQuads / 2) * 2; }
};

// K for a view: the worst case over the view of pixels per unit of
// perpendicular offset at unit Euclidean distance.
double lodPixelsPerUnit(const RenderView& view);

LodSelection selectLod(const LodInput& in);

// The full-resolution mesh's height at a sample-space position (the two
// triangles per cell, split (i,j)-(i+1,j+1)): what LOD error is measured
// against.
float fullMeshHeightAt(const terrain::Heightfield& hf, const glm::dvec2& samplePos);

}  // namespace hs::render
