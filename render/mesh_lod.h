#pragma once
// Which level of a mesh asset's LOD chain an instance draws: the coarsest
// whose error, projected to the screen at the instance's distance, is within
// the scene's pixel bound (SceneSettings::meshLodErrorPixels), by
// mesh::selectLod. GL-free, so tests and statistics can ask what the
// renderer draws.
//
// The distance is to the nearest point of the instance's bounding sphere, so
// the bound holds for every point of the mesh (an eye inside the sphere
// draws level 0). Errors are in the mesh's own metres and grow with the
// instance's largest scale.
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"

namespace hs::render {

struct MeshLodChoice {
  int level = 0;
  double distance = 0.0;              // metres, eye to the bounding sphere (0 inside it)
  double projectedErrorPixels = 0.0;  // of the chosen level
};

// `errors`: per level in metres, level 0 first (MeshAsset::lodErrors()).
// `centreRel`: the bounding sphere's centre relative to the eye (world
// orientation), `radius` in the mesh's units, `worldScale` the instance's
// largest scale factor.
MeshLodChoice chooseMeshLod(const std::vector<double>& errors, const glm::dvec3& centreRel, double radius,
                            double worldScale, const RenderView& view, double thresholdPixels);

}  // namespace hs::render
