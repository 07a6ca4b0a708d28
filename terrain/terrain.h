#pragma once
// One terrain object of a scene: heights (with holes and georeferencing) and
// paint layers on the same grid. A scene with several terrains holds several.
#include <vector>

#include "terrain/heightfield.h"
#include "terrain/paint_layers.h"

namespace hs::terrain {

struct Terrain {
  Heightfield height;
  PaintLayers paint;

  static Result<Terrain> create(const HeightfieldDesc& desc, std::vector<Material> materials = {});
  // Wraps an existing heightfield (e.g. a DEM import) with default paint layers.
  static Result<Terrain> fromHeightfield(Heightfield hf, std::vector<Material> materials = {});
  Terrain clone() const { return Terrain{height.clone(), paint.clone()}; }
  size_t memoryBytes() const { return height.memoryBytes() + paint.memoryBytes(); }
};

}  // namespace hs::terrain
