#pragma once
// Octahedral impostors (the far level of an instanced source's types,
// render/instanced_source.h): the geometry of their atlas, GL-free, so the
// bake (impostor_cache.h), the shaders (shaders/impostor.glsl is the same
// maths in float) and tests agree.
//
// A mesh is photographed from kImpostorFrames x kImpostorFrames directions
// over the upper hemisphere, laid out by the hemi-octahedral map: a unit
// direction d (z up, d.z >= 0) goes to the octahedron |x| + |y| + z = 1,
// whose square of (x + y, x - y) covers [-1, 1]^2; frame (i, j) looks from
// the direction at grid point (i, j) / (N - 1), so the border frames look
// along the horizon and the centre one straight down. Each frame is an
// orthographic picture of level 0's bounding sphere (centre c, radius r) in
// a square of kImpostorFramePixels, the frame's right and up axes spanning
// [-r, r]. Foliage is seen from above or level (the ground hides its
// underside), hence the hemisphere: a view from below takes the horizon's
// frames.
//
// Drawing blends the three frames around the view direction (the corners
// of the grid triangle it falls in, barycentric weights), so the picture
// turns smoothly instead of jumping from frame to frame.
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "foliage/impostor_images.h"

namespace hs::render {

// Per side of the grid (144 frames) and of a frame (a 768 x 768 atlas):
// declared with the stored images, which must have this layout.
using foliage::kImpostorFrames;
using foliage::kImpostorFramePixels;

// The grid point (each coordinate in [0, 1]) of unit direction `d` (below
// the horizon: projected onto it).
glm::dvec2 hemiOctEncode(const glm::dvec3& d);
// The unit direction of grid point `g` (each coordinate in [0, 1]).
glm::dvec3 hemiOctDecode(const glm::dvec2& g);
// The direction frame (i, j) looks from (towards the viewer, unit).
glm::dvec3 impostorFrameDirection(int i, int j);

// A frame's picture plane: right and up (unit, orthogonal to each other
// and to `d`). right = z x d normalised (x for the frame straight down).
struct ImpostorBasis {
  glm::dvec3 right, up;
};
ImpostorBasis impostorBasis(const glm::dvec3& d);

// The three frames a view from direction `d` blends, and their weights
// (non-negative, summing to 1).
struct ImpostorBlend {
  std::array<glm::ivec2, 3> frames;
  glm::dvec3 weights;
};
ImpostorBlend impostorBlend(const glm::dvec3& d);

// The largest angle (radians) between a direction of the upper hemisphere
// and the frame nearest it (measured once over a fine grid).
double impostorCoveringAngle();

// A bound on how far (metres, mesh space) the impostor of a mesh whose
// level-0 bounding sphere has radius `radius` may draw a surface point from
// where the mesh draws it: a point off the picture plane by up to r seen
// from the covering angle away moves by r sin(angle) (the depth atlas
// takes most of that back, no credit taken for it), and a frame's texel
// spans 2r / kImpostorFramePixels. The LOD rule (mesh_lod.h) takes this as
// the impostor level's error; bench/render/bench_foliage_render measures
// the image error it gives.
double impostorError(double radius);

}  // namespace hs::render
