#pragma once
// Scenes for the transparency suite (test_oit.cpp): translucent quads
// stacked in front of an opaque backdrop, seen from above, so each pixel's
// depth complexity is known by construction.
#include <glm/glm.hpp>

#include <string>

#include "look_from.h"
#include "scene_parts.h"
#include "mesh/primitives.h"
#include "render/render_view.h"
#include "scene/scene_state.h"

namespace hs::test {

struct OitScene {
  scene::SceneState state;
  render::RenderView view;
};

// A square mesh asset `id` (gridPlane, facing +Z) with its own material
// `id`: `color`, `opacity`, unlit or lit.
inline void addQuadAsset(scene::SceneState& s, uint32_t id, float size, glm::vec3 color, float opacity, bool unlit) {
  addMeshAsset(s, id, "Quad " + std::to_string(id), mesh::gridPlane(size, 1), color, opacity, unlit);
}

inline void addInstance(scene::SceneState& s, uint32_t entity, uint32_t asset, glm::dvec3 at) {
  scene::Entity e;
  e.id = entity;
  e.name = "Layer " + std::to_string(entity);
  e.mesh = scene::MeshInstance{asset};
  e.transform.translation = at;
  s.roots.push_back(e.id);
  s.entities.emplace(e.id, e);
}

// An opaque unlit backdrop at z = -1 and `layers` translucent quads above
// it (z = 0, 0.2, 0.4, ...), each its own colour and opacity, offset so the
// image has pixels of every depth complexity from 0 to `layers`; lit ones
// with a sun when `lit`. The camera looks down from z = 8.
inline OitScene stackScene(int layers, bool lit, int size = 96) {
  OitScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = lit ? 0.3f : 0.0f;
  addQuadAsset(s, 1, 8.0f, {0.2f, 0.3f, 0.5f}, 1.0f, true);
  addInstance(s, 1, 1, {0, 0, -1});
  for (int i = 0; i < layers; ++i) {
    const uint32_t id = uint32_t(2 + i);
    const glm::vec3 color(0.2f + 0.7f * float(i % 3 == 0), 0.2f + 0.7f * float(i % 3 == 1), 0.2f + 0.6f * float(i % 3 == 2));
    addQuadAsset(s, id, 2.0f + 0.3f * float(i), color, 0.25f + 0.1f * float(i % 5), !lit);
    addInstance(s, id, id, {0.15 * (i % 2 ? 1 : -1) * i, 0.1 * i, 0.2 * i});
  }
  if (lit) addSun(s, 1000, {40, 0, -20});
  out.view.width = out.view.height = size;
  out.view.fovY = glm::radians(40.0);
  out.view.eye = {0.0, 0.0, 8.0};
  out.view.orientation = lookFrom(out.view.eye, {0, 0.001, 0}).rotation;
  return out;
}

// `layers` copies of one translucent unlit quad (colour `color`, opacity
// `opacity`) over the backdrop, all covering the whole view: every pixel
// has depth complexity `layers`.
inline OitScene deepScene(int layers, glm::vec3 color, float opacity, int size = 48) {
  OitScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.0f;
  addQuadAsset(s, 1, 20.0f, {0.1f, 0.1f, 0.6f}, 1.0f, true);
  addInstance(s, 1, 1, {0, 0, -1});
  addQuadAsset(s, 2, 20.0f, color, opacity, true);
  for (int i = 0; i < layers; ++i) addInstance(s, uint32_t(2 + i), 2, {0, 0, 0.004 * i});
  out.view.width = out.view.height = size;
  out.view.fovY = glm::radians(30.0);
  out.view.eye = {0.0, 0.0, 8.0};
  out.view.orientation = lookFrom(out.view.eye, {0, 0.001, 0}).rotation;
  return out;
}

}  // namespace hs::test
