#pragma once
// Scenes for the material suites: one lit sphere (or plane) seen head-on,
// its material given, with a sun of known direction and colour and no
// ambient light, so a pixel's linear value can be computed by hand.
#include <glm/glm.hpp>

#include <string>

#include "look_from.h"
#include "mesh/primitives.h"
#include "render/render_view.h"
#include "scene/light_units.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

struct MaterialScene {
  scene::SceneState state;
  scene::MaterialId material = scene::kNoMaterial;
  glm::dvec3 toSun{0.0};    // unit, world
  glm::vec3 sunColor{0.0f};  // linear, scene units (light_units.h lightRadiometricColor)
  render::RenderView view;
};

// `mesh` as asset 1 with `material` (id 1, named "NAME / material" unless
// it has a name) in every slot, shown by entity 1 named `name` at the
// origin, a root. Returns that entity, for the caller to place.
inline scene::Entity& addMeshEntity(scene::SceneState& s, mesh::MeshData mesh, const scene::Material& material,
                                    const std::string& name) {
  scene::MeshAsset a;
  a.id = 1;
  a.name = name;
  a.contentHash = mesh::contentHash(mesh);
  a.data = std::make_shared<const mesh::MeshData>(std::move(mesh));
  scene::Material m = material;
  m.id = 1;
  m.asset = a.id;
  if (m.name.empty()) m.name = name + " / material";
  a.materialSlots.assign(scene::materialSlotCount(*a.data), m.id);
  s.materials.emplace(m.id, m);
  s.assets.emplace(a.id, a);

  scene::Entity e;
  e.id = 1;
  e.name = name;
  e.mesh = scene::MeshInstance{a.id};
  s.roots.push_back(e.id);
  return s.entities.emplace(e.id, e).first->second;
}

// `mesh` at the origin with one document material per slot (the first is
// `material`), a sun shining from the upper left front, the camera on -Y
// looking at the origin from `distance` metres. Tone mapping, grid,
// anti-aliasing and ambient light are off.
inline MaterialScene materialScene(mesh::MeshData mesh, const scene::Material& material, int size = 160,
                                   double distance = 4.0) {
  MaterialScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.0f;
  s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = glm::vec3(0.0f);

  const scene::Entity& e = addMeshEntity(s, std::move(mesh), material, "Sample");
  out.material = s.assets.at(e.mesh->mesh).materialSlots.front();

  scene::Entity sun;
  sun.id = 2;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.light->color = glm::vec3(1.0f);
  // A white surface facing it returns 2 in scene units (scene/light_units.h).
  sun.light->intensity = float(scene::legacyLightIntensity(scene::Light::Type::Sun, 2.0));
  sun.transform.rotation = scene::fromEulerDegrees({50, 0, -30});
  s.entities.emplace(sun.id, sun);
  s.roots.push_back(sun.id);
  out.toSun = -glm::normalize(sun.transform.rotation * glm::dvec3(0, 0, -1));
  out.sunColor = scene::lightRadiometricColor(*sun.light);

  out.view.width = out.view.height = size;
  out.view.fovY = glm::radians(36.0);
  out.view.eye = {0.0, -distance, 0.0};
  out.view.orientation = lookFrom(out.view.eye, {0, 0, 0}).rotation;
  return out;
}

}  // namespace hs::test
