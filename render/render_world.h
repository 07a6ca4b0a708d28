#pragma once
// What the renderer draws, taken from the document once per frame (after
// Godot's scene -> servers split): world matrices composed in double, the
// lights with their world positions and directions, the mesh instances and
// terrains that are visible. Passes read this, never the document itself,
// so one frame's data is built once however many views draw it.
#include <optional>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene_state.h"

namespace hs::render {

struct WorldLight {
  scene::EntityId entity = scene::kNoEntity;
  scene::Light::Type type = scene::Light::Type::Sun;
  glm::dvec3 position{0.0};   // world
  glm::dvec3 direction{0.0, 0.0, -1.0};  // the way the light travels (world, unit)
  glm::vec3 color{0.0f};      // scene units (scene/light_units.h lightRadiometricColor): sun
                              // illuminance, point/spot luminous intensity (÷ d² in the shader)
  float range = 100.0f;
  float cosInnerHalf = 1.0f;  // spot: cosine of half the inner and outer cone angles
  float cosOuterHalf = 0.0f;
  bool castsShadows = false;
  int shadowResolution = 0;   // texels per side; 0: from the settings
};

struct MeshInstanceRef {
  scene::EntityId entity = scene::kNoEntity;
  const scene::MeshAsset* asset = nullptr;
  glm::dmat4 world{1.0};
  glm::vec3 tint{1.0f};
};

struct RenderWorld {
  const scene::SceneState* state = nullptr;
  std::unordered_map<scene::EntityId, glm::dmat4> world;  // every entity
  std::optional<WorldLight> sun;       // the first visible sun in outliner order
  std::vector<WorldLight> lights;      // the other lights, outliner order
  std::vector<MeshInstanceRef> meshes; // visible mesh instances with data
  std::vector<scene::EntityId> terrains;  // visible terrain entities

  static RenderWorld build(const scene::SceneState& state);
};

}  // namespace hs::render
