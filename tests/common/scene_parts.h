#pragma once
// Parts the render suites and benchmarks build their scenes from (one copy
// each): a mesh asset with a material of its own, an entity showing it, and
// a sun.
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"
#include "scene/light_units.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

// Mesh asset `id` named `name`, every material slot on its own material
// (also id `id`): `color`, `opacity`, unlit or lit.
inline void addMeshAsset(scene::SceneState& s, scene::AssetId id, const std::string& name, mesh::MeshData mesh,
                         glm::vec3 color, float opacity = 1.0f, bool unlit = false) {
  scene::MeshAsset a;
  a.id = id;
  a.name = name;
  a.contentHash = mesh::contentHash(mesh);
  a.data = std::make_shared<const mesh::MeshData>(std::move(mesh));
  scene::Material m;
  m.id = id;
  m.asset = id;
  m.name = name + " / material";
  m.baseColor = color;
  m.opacity = opacity;
  m.unlit = unlit;
  a.materialSlots.assign(scene::materialSlotCount(*a.data), m.id);
  s.materials.emplace(m.id, m);
  s.assets.emplace(a.id, a);
}

// A root entity `id` named `name` showing mesh asset `asset` at `translation`.
inline void addMeshEntity(scene::SceneState& s, scene::EntityId id, const std::string& name, scene::AssetId asset,
                          glm::dvec3 translation = glm::dvec3(0.0)) {
  scene::Entity e;
  e.id = id;
  e.name = name;
  e.mesh = scene::MeshInstance{asset};
  e.transform.translation = translation;
  s.entities.emplace(e.id, e);
  s.roots.push_back(e.id);
}

// A root sun entity `id` turned by `eulerDegrees`, at `relative` times the
// legacy unit intensity.
inline void addSun(scene::SceneState& s, scene::EntityId id, glm::dvec3 eulerDegrees, bool castsShadows = false,
                   double relative = 1.0) {
  scene::Entity sun;
  sun.id = id;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.light->intensity = float(scene::legacyLightIntensity(scene::Light::Type::Sun, relative));
  sun.light->castsShadows = castsShadows;
  sun.transform.rotation = scene::fromEulerDegrees(eulerDegrees);
  s.entities.emplace(sun.id, sun);
  s.roots.push_back(sun.id);
}

}  // namespace hs::test
