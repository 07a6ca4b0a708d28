#pragma once
// The sun's cascaded shadow maps as numbers (no GL): where the cascades
// split the view's depth, the world box each one covers and the matrices
// that take a position into its map. docs/rendering.md "Shadows" explains
// the scheme; in short:
//
// - Splits are "practical" (Zhang et al.): a blend of logarithmic and
//   uniform splits, lambda = kShadowSplitLambda.
// - Each cascade is stabilised: its map covers the bounding sphere of its
//   slice of the view frustum, whose radius depends only on the field of
//   view and the split depths (not on where the camera looks), and the
//   sphere's centre is snapped to whole texels in the light's space, in
//   double, on a grid anchored near the camera (kShadowAnchorLattice). A
//   camera moving or turning therefore moves the map's content by whole
//   texels only: no shimmer.
// - Matrices are formed in double around the frame origin (the frame's mono
//   camera) and handed to the GPU relative to it, like every other matrix of
//   the renderer: a scene at UTM coordinates gives the same small floats as
//   one at the origin.
// - One set per frame, from the frame's LOD (mono) view: both eyes of a
//   stereo pair read the same cascades.
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"
#include "scene/scene_state.h"

namespace hs::render {

// Blend of logarithmic (1) and uniform (0) splits. Logarithmic splits give
// every cascade the same texels per pixel on screen; the uniform part is
// weighted by the whole range, so over 30 km even 1% of it puts the first
// split at 80 m (texels 4 screen pixels wide at 10 m with 4 x 4096).
// 0.999 keeps a sliver of it (a few metres at 30 km) and gives, at
// 1920x1080 with 4 cascades of 4096, about 0.7, 0.6, 0.9 and 1.4 pixels per
// texel at 10 m, 100 m, 1 km and 10 km (bench_shadows prints the table).
constexpr double kShadowSplitLambda = 0.999;
// The logarithmic part starts here at the nearest (a 1 cm near plane would
// put every logarithmic split within a metre of the eye).
constexpr double kShadowMinSplitNear = 0.5;
constexpr int kMaxShadowCascades = 4;
// The texel grid is anchored at the lattice point of this spacing nearest
// the camera (metres, world axes), not at the world origin: a scene moved
// by a multiple of it (a scan at UTM coordinates and the same scan at the
// origin) gets its shadow texels at the same places. Crossing from one
// lattice cell to the next (once per 100 m of camera travel) moves the grid
// by a fraction of a texel: a single-frame change at shadow edges.
constexpr double kShadowAnchorLattice = 100.0;

// What the settings ask for, resolved from the quality preset and clamped.
struct ShadowConfig {
  bool enabled = false;
  int resolution = 2048;
  int cascades = 3;
  int pcfRadius = 1;
  double distance = 30000.0;
};
// The preset (or, with Custom, the explicit fields), each clamped to its
// range (scene/fields.cpp: the same bounds) and the resolution to
// `maxTextureSize`. `problem` names the field of a value that had to be
// clamped ("settings.shadow_resolution: 0 is out of range (256 to 8192),
// using 256"), empty otherwise.
ShadowConfig resolveShadowConfig(const scene::SceneSettings& settings, int maxTextureSize, std::string* problem);

struct ShadowCascade {
  double splitNear = 0.0, splitFar = 0.0;  // view depth the cascade serves (m)
  double radius = 0.0;        // half the width of the map in metres
  double texelMetres = 0.0;   // world size of one texel
  glm::dvec3 centreLight{0.0};  // the snapped centre in light space, relative to the anchor (m)
  // Frame-origin-relative position -> light clip space (x, y in -1..1,
  // depth 0..1 with 1 on the sun's side, drawn with depth clamp).
  glm::dmat4 frameToClip{1.0};
  // The same into map coordinates (u, v, depth in 0..1): the lookup matrix.
  glm::dmat4 frameToMap{1.0};
};

struct SunCascades {
  glm::dmat3 lightRotation{1.0};  // world -> light space (z towards the sun)
  glm::dvec3 frameOrigin{0.0};
  glm::dvec3 anchor{0.0};  // the texel grid's origin (kShadowAnchorLattice)
  std::vector<ShadowCascade> cascades;
};

// Cascades of the sun (travelling along `sunDirection`, unit, world) for
// `view`, with matrices relative to `frameOrigin`.
SunCascades computeSunCascades(const RenderView& view, const glm::dvec3& sunDirection, const ShadowConfig& config,
                               const glm::dvec3& frameOrigin);

// Split depths (config.cascades + 1 values from the near plane to the far one).
std::vector<double> cascadeSplits(double nearClip, double farClip, int cascades);

}  // namespace hs::render
