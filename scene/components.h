#pragma once
// Components an entity can carry. Plain values: copying an entity copies its
// components, which is what undo snapshots rely on. Their fields are listed
// in fields.cpp, from which the property panel, the JSON file format and
// animation tracks all work.
#include <glm/glm.hpp>

#include "scene/ids.h"

namespace hs::scene {

struct MeshInstance {
  AssetId mesh = kNoAsset;
  glm::vec3 tint{1.0f};  // multiplies the material colour (linear)
  bool operator==(const MeshInstance&) const = default;
};

// A sun shines along the entity's local -Z axis (as in Blender); a point
// light sits at the entity's position.
struct Light {
  enum class Type { Sun = 0, Point = 1 };
  Type type = Type::Sun;
  glm::vec3 color{1.0f, 0.96f, 0.9f};  // linear RGB
  float intensity = 2.2f;              // sun: irradiance scale; point: at 1 m
  float range = 100.0f;                // point lights: distance where they fade out
  bool operator==(const Light&) const = default;
};

// Looks along local -Z with local +Y up (as in Blender). Stereo settings
// feed sequencer::stereoCameras(); Mono renders the camera itself.
struct Camera {
  enum class Stereo { Mono = 0, OffAxis = 1, Parallel = 2, ToeIn = 3 };
  enum class Pivot { Left = 0, Centre = 1, Right = 2 };
  double verticalFovDeg = 50.0;
  double nearClip = 0.1;        // metres
  double farClip = 50000.0;     // metres
  double focusDistance = 10.0;  // metres (depth of field)
  double fStop = 8.0;           // aperture (depth of field)
  Stereo stereo = Stereo::Mono;
  double interaxial = 0.065;    // metres between the eyes
  double convergence = 10.0;    // metres to the zero-parallax plane
  Pivot pivot = Pivot::Centre;
  bool operator==(const Camera&) const = default;
};

// Shows a terrain of the document (SceneState::terrains). The entity's world
// translation moves it (added to the terrain's own double origin); rotation
// and scale are ignored: heights are elevations on a north-up grid of true
// ground size, which DEM exports, erosion and slope rules rely on
// (docs/terrain.md). Several entities may show the same terrain.
struct TerrainInstance {
  TerrainId terrain = kNoTerrain;
  double lodErrorPixels = 1.0;  // screen-space error bound of the LOD, pixels
  bool operator==(const TerrainInstance&) const = default;
};

// Full-frame sensor height (36 x 24 mm), for focal length <-> field of view.
constexpr double kSensorHeightMm = 24.0;

}  // namespace hs::scene
