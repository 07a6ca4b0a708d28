#pragma once
// The post-processing tests' scene and view (test_post_chain,
// test_stylised): a lit grey ground, balls from dark to a bright emitter
// (exposed values from about 0.01 to 30) and an HDR sky: every part of each
// tone curve, edges of every contrast for the stylised effects.
#include "mesh/primitives.h"
#include "render/render_view.h"
#include "scene/scene_state.h"
#include "look_from.h"
#include "scene_parts.h"

namespace hs::test {

inline scene::SceneState postTestScene() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.skyZenith = {6.0f, 9.0f, 14.0f};
  s.settings.skyHorizon = {0.6f, 0.7f, 0.8f};
  addMeshAsset(s, 1, "Ground", mesh::gridPlane(60.0f, 1), {0.4f, 0.4f, 0.38f});
  addMeshEntity(s, 1, "Ground", 1);
  const glm::vec3 colours[] = {{0.02f, 0.02f, 0.03f}, {0.8f, 0.2f, 0.1f}, {0.1f, 0.7f, 0.2f}, {0.9f, 0.9f, 0.9f}};
  for (int i = 0; i < 4; ++i) {
    addMeshAsset(s, 10 + i, "Ball " + std::to_string(i), mesh::uvSphere(0.8f, 24, 12), colours[i]);
    addMeshEntity(s, 10 + i, "Ball " + std::to_string(i), 10 + i, {-3.0 + 2.0 * i, 0.0, 0.8});
  }
  // An emitter: exposed radiance far above 1 (highlights to compress, light to bloom).
  addMeshAsset(s, 20, "Lamp", mesh::uvSphere(0.3f, 16, 8), {0.0f, 0.0f, 0.0f});
  scene::Material& lamp = s.materials.at(20);
  lamp.emission = {1.0f, 0.6f, 0.3f};
  lamp.emissionStrength = 40.0f;
  addMeshEntity(s, 20, "Lamp", 20, {0.0, -1.5, 2.2});
  addSun(s, 100, {50, 0, -30});
  return s;
}

inline render::RenderView postTestView(int w = 192, int h = 108) {
  render::RenderView v;
  v.width = w;
  v.height = h;
  v.fovY = glm::radians(55.0);
  v.eye = {0.0, -9.0, 2.5};
  v.orientation = lookFrom(v.eye, {0.0, 0.0, 1.2}).rotation;
  return v;
}

// A root camera entity `id` at `eye` looking at `at`, with postTestView's
// field of view (the tests of cameras' exposure and post settings).
inline void addPostTestCamera(scene::SceneState& s, scene::EntityId id, const char* name, glm::dvec3 eye,
                              glm::dvec3 at) {
  scene::Entity c;
  c.id = id;
  c.name = name;
  c.camera = scene::Camera{};
  c.camera->verticalFovDeg = 55.0;
  c.transform = lookFrom(eye, at);
  s.entities.emplace(c.id, c);
  s.roots.push_back(c.id);
}

}  // namespace hs::test
