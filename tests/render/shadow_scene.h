#pragma once
// The shadow tests' scene: a 40 x 40 m ground plane, three spheres and a
// slab standing on it, a low sun (20 degrees up), a camera looking over
// it; the same triangles in world space for the CPU ray cast.
#include <memory>

#include "look_from.h"
#include "mesh/mesh_data.h"
#include "mesh/primitives.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

struct ShadowScene {
  scene::SceneState state;
  mesh::MeshData world;  // every triangle, world coordinates minus `offset`
  glm::dvec3 offset{0.0};
};

inline scene::EntityId addShadowEntity(scene::SceneState& s, scene::Entity e) {
  e.id = s.maxEntityId() + 1;
  s.roots.push_back(e.id);
  const scene::EntityId id = e.id;
  s.entities.emplace(id, std::move(e));
  return id;
}

// `m` as a new asset (with a copy of `material` in every slot when one is
// given), shown by a new root entity "shape" at `at`, scaled by `scale`.
inline scene::EntityId addShadowMesh(scene::SceneState& s, mesh::MeshData m, glm::dvec3 at,
                                     glm::dvec3 scale = glm::dvec3(1.0), const scene::Material* material = nullptr) {
  scene::MeshAsset a;
  a.id = s.maxAssetId() + 1;
  a.name = "shape";
  a.contentHash = mesh::contentHash(m);
  a.data = std::make_shared<const mesh::MeshData>(std::move(m));
  if (material) {
    scene::Material mat = *material;
    mat.id = scene::MaterialId(s.materials.size() + 1);
    mat.asset = a.id;
    a.materialSlots.assign(scene::materialSlotCount(*a.data), mat.id);
    s.materials.emplace(mat.id, mat);
  }
  const scene::AssetId id = a.id;
  s.assets.emplace(id, std::move(a));
  scene::Entity e;
  e.name = "shape";
  e.mesh = scene::MeshInstance{id};
  e.transform.translation = at;
  e.transform.scale = scale;
  return addShadowEntity(s, e);
}

inline ShadowScene shadowScene(glm::dvec3 offset = glm::dvec3(0.0), double sunElevationDeg = 20.0) {
  ShadowScene out;
  out.offset = offset;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.shadows = true;
  s.settings.shadowQuality = scene::ShadowQuality::Custom;
  s.settings.shadowResolution = 1024;
  s.settings.shadowCascades = 2;
  s.settings.shadowPcfRadius = 1;
  s.settings.shadowDistance = 80.0;
  auto addMesh = [&](mesh::MeshData m, glm::dvec3 at, glm::dvec3 scale) {
    // World triangles for the reference.
    const uint32_t base = uint32_t(out.world.positions.size());
    for (const glm::vec3& p : m.positions)
      out.world.positions.push_back(glm::vec3(glm::dvec3(p) * scale + at));
    for (uint32_t i : m.indices) out.world.indices.push_back(base + i);
    addShadowMesh(s, std::move(m), offset + at, scale);
  };
  addMesh(mesh::gridPlane(40.0f, 8), {0, 0, 0}, {1, 1, 1});
  addMesh(mesh::uvSphere(1.0f, 48, 24), {-3, 2, 1.0}, {1, 1, 1});
  addMesh(mesh::uvSphere(1.0f, 48, 24), {2, 5, 1.6}, {1, 1, 1});
  addMesh(mesh::uvSphere(1.0f, 48, 24), {4, -1, 0.6}, {0.6, 0.6, 0.6});
  addMesh(mesh::gridPlane(1.0f, 1), {-1, 7, 1.5}, {3, 3, 1});  // a floating slab: its shadow is detached
  out.world.submeshes.push_back({0, uint32_t(out.world.indices.size()), -1});
  scene::Entity sun;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.light->castsShadows = true;
  // Local -Z rotated up by (90 - elevation) about X, then about Z.
  sun.transform.rotation = scene::fromEulerDegrees({90.0 - sunElevationDeg, 0, 150});
  addShadowEntity(s, sun);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 50.0;
  cam.transform = lookFrom(offset + glm::dvec3(0, -14, 7), offset + glm::dvec3(0, 3, 0));
  addShadowEntity(s, cam);
  return out;
}

// The same ground and shapes lit by one spot or point light alone (the sun
// hidden), casting shadows: the spot from above and behind the camera's
// target, its 100-degree cone over the shapes; the point light among the
// spheres, so its shadows fall on several faces of its cube.
inline ShadowScene localLightScene(scene::Light::Type type, glm::dvec3 offset = glm::dvec3(0.0)) {
  ShadowScene out = shadowScene(offset);
  scene::SceneState& s = out.state;
  for (auto& [id, e] : s.entities)
    if (e.light) e.visible = false;
  scene::Entity e;
  e.name = type == scene::Light::Type::Spot ? "Test spot" : "Test point";
  e.light = scene::Light{};
  e.light->type = type;
  e.light->intensity = 2.0e6f;
  e.light->range = 60.0f;
  e.light->innerConeDeg = 80.0f;
  e.light->outerConeDeg = 100.0f;
  e.light->castsShadows = true;
  e.transform = type == scene::Light::Type::Spot ? lookFrom(offset + glm::dvec3(1.0, -3.0, 9.0), offset + glm::dvec3(0, 3, 0))
                                                  : lookFrom(offset + glm::dvec3(0.5, 1.0, 3.5), offset);
  addShadowEntity(s, e);
  return out;
}

}  // namespace hs::test
