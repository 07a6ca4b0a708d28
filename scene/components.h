#pragma once
// Components an entity can carry. Plain values: copying an entity copies its
// components, which is what undo snapshots rely on. Their fields are listed
// in fields.cpp, from which the property panel, the JSON file format and
// animation tracks all work.
#include <map>
#include <string>

#include <glm/glm.hpp>

#include "particles/emitter.h"
#include "scene/field_value.h"
#include "scene/ids.h"

namespace hs::scene {

struct MeshInstance {
  AssetId mesh = kNoAsset;
  glm::vec3 tint{1.0f};  // multiplies the material colour (linear)
  bool operator==(const MeshInstance&) const = default;
};

// A sun shines along the entity's local -Z axis (as in Blender); a point
// light sits at the entity's position; a spot sits there and shines along
// local -Z.
//
// Intensity is in physical units, as in Filament and Unreal:
//   sun:          illuminance in lux on a surface facing it (100 000: noon sun)
//   point, spot:  luminous power in lumens (800: a 60 W bulb)
// The renderer turns power into luminous intensity (candela):
//   point:  I = Φ / 4π
//   spot:   I = Φ / (2π (1 − cos(outer/2))), the power spread over the
//           outer cone's solid angle, so narrowing the cone brightens the
//           beam and the light's total power stays what the user set
//           (Filament's "focused" spot); between the inner and the outer
//           cone the beam falls off smoothly to 0.
// Illuminance at distance d is I / d², windowed to 0 at `range`
// (docs/rendering.md "Lights"). scene/light_units.h holds the conversions;
// what these values look like on screen is set by the exposure
// (SceneSettings::exposureEv100).
struct Light {
  enum class Type { Sun = 0, Point = 1, Spot = 2 };
  Type type = Type::Sun;
  glm::vec3 color{1.0f, 0.96f, 0.9f};  // linear RGB
  float intensity = 100000.0f;         // sun: lux; point and spot: lumens
  float range = 100.0f;                // point and spot: metres where they fade out to 0
  float innerConeDeg = 30.0f;          // spot: full apex angle of the undimmed beam, degrees
  float outerConeDeg = 45.0f;          // spot: full apex angle where the beam reaches 0, degrees
  bool castsShadows = false;
  int shadowResolution = 0;            // shadow map texels per side; 0: from settings.shadow_quality
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
  // The scene's post settings this camera overrides, per field (as in
  // Unreal's camera post-process settings): key "bloom.intensity" for the
  // setting "post.bloom.intensity", "tonemap" for "tonemap"; the fields
  // are "camera.post.<key>" (scene/camera_post.h, which applies them).
  std::map<std::string, FieldValue> post;
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

// A particle emitter (docs/particles.md, "In the document"). The emitter's
// world origin is the entity's world translation plus desc.origin (an offset,
// usually 0); rotation and scale are ignored, like a terrain's: directions,
// gravity and wind are world vectors (Z up). The particles at scene time t
// are a pure function of desc and t (particles/evaluate.h). One emitter per
// entity: a preset with several (a torch: flame and smoke) is a parent with
// an emitter child each, so `set EMITTER particles.FIELD` names one.
struct ParticleEmitter {
  particles::EmitterDesc desc{};
  bool operator==(const ParticleEmitter&) const = default;
};

// Full-frame sensor height (36 x 24 mm), for focal length <-> field of view.
constexpr double kSensorHeightMm = 24.0;

}  // namespace hs::scene
