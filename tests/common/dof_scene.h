#pragma once
// Depth of field's test scenes (test_dof_render, bench_dof): unlit surfaces
// (the colour is the texture's, whatever the light) seen by a 20-degree
// camera with the lens in the scene's camera entity, so every mode reads
// focal length, f-stop and focus distance the way a document does.
//   - partialOcclusion: a checkerboard wall 12 m away (in focus) and a thin
//     white pole 2 m away, blurred wider than it is, so the wall shows
//     through its blurred edges (and through the pole itself) in the
//     lens-averaged reference.
//   - focusPoint: a small bright square at the focus distance (8 m) in
//     front of the same wall, out of focus behind it.
// Header-only; needs hs_render, hs_scene, hs_mesh.
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/image.h"
#include "look_from.h"
#include "mesh/primitives.h"
#include "render/render_view.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

struct DofScene {
  scene::SceneState state;
  scene::EntityId camera = 0;
  render::RenderView view(int width, int height) const { return render::viewFromCamera(state, camera, width, height); }
};

namespace dof_detail {

inline scene::MaterialId addUnlit(scene::SceneState& s, const std::string& name, glm::vec3 colour,
                                  scene::TextureId texture = 0) {
  scene::Material m;
  m.id = s.maxMaterialId() + 1;
  m.name = name;
  m.baseColor = colour;
  m.baseColorTexture = texture;
  m.unlit = true;
  m.twoSided = true;
  s.materials.emplace(m.id, m);
  return m.id;
}

// A vertical plane facing the camera (gridPlane turned to XZ), `w` x `h`
// metres, centred at `at`.
inline void addPanel(scene::SceneState& s, scene::MaterialId material, glm::dvec3 at, double w, double h,
                     float uvRepeat = 1.0f) {
  scene::MeshAsset a;
  a.id = s.maxAssetId() + 1;
  a.name = "panel";
  mesh::MeshData m = mesh::gridPlane(1.0f, 1, uvRepeat);
  a.contentHash = mesh::contentHash(m) ^ a.id;
  a.data = std::make_shared<const mesh::MeshData>(std::move(m));
  a.materialSlots.assign(scene::materialSlotCount(*a.data), material);
  scene::Entity e;
  e.id = s.maxEntityId() + 1;
  e.name = "panel " + std::to_string(e.id);
  e.mesh = scene::MeshInstance{a.id};
  e.transform.translation = at;
  e.transform.rotation = scene::fromEulerDegrees({90, 0, 0});
  e.transform.scale = {w, h, 1.0};
  s.roots.push_back(e.id);
  s.entities.emplace(e.id, e);
  s.assets.emplace(a.id, std::move(a));
}

// A 64 x 64 checkerboard of 8-texel cells, dark blue and orange (every
// channel changes at an edge).
inline scene::TextureId addChecker(scene::SceneState& s) {
  auto t = std::make_shared<mesh::Texture>();
  t->name = "checker";
  t->width = t->height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool odd = ((x / 8) + (y / 8)) % 2;
      t->rgba.insert(t->rgba.end(), {uint8_t(odd ? 230 : 20), uint8_t(odd ? 140 : 40), uint8_t(odd ? 30 : 120), 255});
    }
  scene::TextureAsset ta;
  ta.id = 1;
  ta.name = t->name;
  ta.srgb = true;
  ta.contentHash = 0xc4ec;
  ta.image = t;
  s.textures.emplace(ta.id, ta);
  return ta.id;
}

inline DofScene baseScene(double focus, double fStop) {
  DofScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.sky = scene::SkyModel::Gradient;
  const scene::MaterialId wall = addUnlit(s, "wall", glm::vec3(1.0f), addChecker(s));
  addPanel(s, wall, {0, 12, 0}, 8.0, 8.0, 4.0f);
  scene::Entity cam;
  cam.id = s.maxEntityId() + 1;
  cam.name = "Lens";
  cam.transform = lookFrom({0, 0, 0}, {0, 1, 0});
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 20.0;
  cam.camera->focusDistance = focus;
  cam.camera->fStop = fStop;
  s.roots.push_back(cam.id);
  s.entities.emplace(cam.id, cam);
  out.camera = cam.id;
  return out;
}

}  // namespace dof_detail

// Focus on the wall (12 m); the pole 2 m away blurs to about 14 px at
// f/1.4 on a 240-pixel-high image (render/dof_lens.h).
inline DofScene partialOcclusionScene(double fStop = 1.4) {
  DofScene out = dof_detail::baseScene(12.0, fStop);
  const scene::MaterialId pole = dof_detail::addUnlit(out.state, "pole", glm::vec3(0.9f, 0.9f, 0.85f));
  dof_detail::addPanel(out.state, pole, {0, 2, 0}, 0.03, 3.0);
  return out;
}

// Focus at 8 m on a 10 cm bright square; the wall behind is blurred.
inline DofScene focusPointScene(double fStop = 1.4) {
  DofScene out = dof_detail::baseScene(8.0, fStop);
  const scene::MaterialId point = dof_detail::addUnlit(out.state, "point", glm::vec3(1.0f, 0.95f, 0.2f));
  dof_detail::addPanel(out.state, point, {0, 8, 0}, 0.1, 0.1);
  return out;
}

// Per-channel error of `a` against `b` (8-bit images of one size) over
// the pixels where `mask` is true (all when empty), in 1/255 units.
struct ImageError {
  double rmse = 0.0, maxError = 0.0, psnr = 0.0;
  size_t pixels = 0;
};
inline ImageError compareImages(const Image& a, const Image& b, const std::vector<bool>& mask = {}) {
  ImageError e;
  double sq = 0.0;
  for (size_t i = 0; i < size_t(a.width) * size_t(a.height); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.rgba8[i * 4 + c]) - double(b.rgba8[i * 4 + c]);
      sq += d * d;
      e.maxError = std::max(e.maxError, std::abs(d));
    }
    ++e.pixels;
  }
  e.rmse = e.pixels ? std::sqrt(sq / double(e.pixels * 3)) : 0.0;
  e.psnr = e.rmse > 0 ? 20.0 * std::log10(255.0 / e.rmse) : std::numeric_limits<double>::infinity();
  return e;
}

}  // namespace hs::test
