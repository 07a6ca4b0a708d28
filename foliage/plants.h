#pragma once
// Built-in plants, so a scene needs no outside assets: parametric trees
// after Weber & Penn ("Creation and Rendering of Realistic Trees", 1995:
// a trunk, levels of child stems placed along their parent with down and
// rotate angles, lengths from a shape function of the position on the
// parent, radii tapering with length, leaf cards on the last level),
// shrubs (several stems from the ground, no trunk), grass clumps (curved
// tapering blades) and rocks (a displaced, flattened icosphere). Each is a
// pure function of its parameters and seed: the same seed gives the same
// mesh, bit for bit. Meshes are Z up, metres, origin at the base; bark and
// rock are submesh 0, leaves and blades submesh 1 with a generated RGBA
// leaf texture whose alpha is the cut-out.
#include <cstdint>
#include <string>
#include <vector>

#include "core/params.h"
#include "mesh/mesh_data.h"
#include "meshproc/lod_chain.h"

namespace hs::foliage {

enum class PlantKind : uint8_t { Broadleaf, Conifer, Shrub, Grass, Rock };

struct PlantParams {
  PlantKind kind = PlantKind::Broadleaf;
  uint64_t seed = 1;
  double height = 12.0;        // metres (grass: blade length; rock: diameter)
  int levels = 2;              // branch levels below the trunk (0..3)
  int branches = 24;           // first-level branches (shrub: stems; grass: blades)
  double leafSize = 0.25;      // metres, a leaf card's side
  int leavesPerBranch = 8;     // on each last-level stem
  int sides = 8;               // around a stem (its roundness)
};

const std::vector<ParamDecl>& plantParamDecls();
// "broadleaf", "conifer", ...
const char* plantKindName(PlantKind k);
// Defaults by kind (a conifer's levels, a grass clump's size).
PlantParams defaultPlant(PlantKind kind, uint64_t seed = 1);

struct PlantStats {
  size_t stems = 0, leaves = 0, triangles = 0;
};

// The plant's mesh; `stats` counts what it made. Parameters out of their
// declared ranges are clamped (warnings appended to `warnings` when given).
mesh::MeshData generatePlant(const PlantParams& p, PlantStats* stats = nullptr,
                             std::vector<std::string>* warnings = nullptr);

// The plant and its LOD chain from the project's decimator (meshproc's
// buildLodChain: each level measured against the full plant, Hausdorff and
// mean error in metres), as an imported asset gets.
mesh::LodChain generatePlantLods(const PlantParams& p, const mesh::LodOptions& options = {},
                                 PlantStats* stats = nullptr);

// The leaf (or blade) texture: size x size RGBA, sRGB, alpha 0 outside.
mesh::Texture leafTexture(PlantKind kind, int size = 64);

}  // namespace hs::foliage
