#pragma once
// Spot and point light shadow maps as numbers (no GL): which lights get a
// map, at what size, and the perspective views that draw them.
// docs/rendering.md "Shadows" ("Spot and point lights") explains the
// scheme; in short:
//
// - A spot gets one perspective map whose frustum holds its outer cone
//   (plus a guard band for the PCF kernel), reaching to its range.
// - A point light gets a cube: six perspective maps along +X, -X, +Y, -Y,
//   +Z, -Z, each a little wider than 90 degrees (the guard band), stored as
//   six layers of the same 2D array as the spots' maps; the shader picks the
//   face from the major axis of light -> point (the point alone, so both
//   eyes pick alike). A spot wider than kSpotAsCubeDeg is drawn as a cube:
//   one perspective map cannot hold it.
// - Depth is reversed like the renderer's: near / distance along the face's
//   axis, 1 at the near plane, towards 0 far away; a point is lit where its
//   depth is at least the stored one (as for the sun).
// - Matrices are formed in double, relative to the frame origin, like the
//   sun's cascades: a light at UTM coordinates gives small floats.
// - One set per frame, drawn once; both eyes of a stereo pair read it.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"
#include "render/render_world.h"
#include "render/shadow_cascades.h"

namespace hs::render {

// A spot wider than this (full outer cone, degrees) is drawn as a cube.
constexpr double kSpotAsCubeDeg = 120.0;
// Per-light map sizes, as settings.shadow_resolution allows.
constexpr int kMinLocalShadowResolution = 256;
constexpr int kMaxLocalShadowResolution = 8192;

struct LocalShadowFace {
  // Frame-origin-relative position -> light clip space (reversed depth,
  // [0, 1]); divide by w.
  glm::dmat4 frameToClip{1.0};
  // The same into map coordinates (u, v in 0..1 of the light's own map, depth).
  glm::dmat4 frameToMap{1.0};
  glm::dvec3 axis{0.0, 0.0, -1.0};  // world direction the face looks along
};

struct LocalShadow {
  size_t light = 0;          // index into RenderWorld::lights (and the frame's light buffer)
  int resolution = 0;        // texels per side of each face
  double tanHalfFov = 1.0;   // of each face, guard band included
  double nearPlane = 0.05;   // metres
  double range = 0.0;
  glm::dvec3 position{0.0};  // frame-relative
  std::vector<LocalShadowFace> faces;  // 1 (spot) or 6 (cube: +X, -X, +Y, -Y, +Z, -Z)
  // World size of one texel at 1 m along the face's axis (the receivers'
  // normal offset scales it by their distance).
  double texelPerMetre() const { return 2.0 * tanHalfFov / double(resolution); }
};

// The map size of a light: its own shadow_resolution, or with 0 the
// settings' (config.resolution for a spot, half of it for each face of a
// cube, whose face covers 90 degrees against a cascade's whole view),
// clamped to kMin/kMaxLocalShadowResolution and `maxTextureSize`. A value
// that had to be clamped adds a message naming the light and the field to
// `problem` ("light 'Lantern': shadow_resolution: -5 is out of range (256
// to 8192), using 256").
int localShadowResolution(const WorldLight& light, const std::string& name, const ShadowConfig& config,
                          int maxTextureSize, std::string* problem);

// Whether the light reaches anything a view can see: its sphere of range
// against each view's frustum (positions in world space).
bool lightReachesViews(const WorldLight& light, const std::vector<RenderView>& views);

// The faces of a shadow-casting point or spot light, relative to `frameOrigin`.
// `pcfRadius` sizes the guard band (the kernel's taps stay inside the map).
LocalShadow computeLocalShadow(const WorldLight& light, size_t index, int resolution, int pcfRadius,
                               const glm::dvec3& frameOrigin);

// The face's volume as planes, frame-relative (terrain_lod.h's node culling
// and the casters' spheres): the frustum from the near plane to the range.
Frustum localShadowVolume(const LocalShadow& shadow, const LocalShadowFace& face);

}  // namespace hs::render
