#include "app/plant_preview.h"

#include <algorithm>
#include <cmath>

#include "app/preview_renderer.h"
#include "scene/foliage_ops.h"
#include "scene/mesh_materials.h"
#include "sequencer/camera_path.h"

namespace hs::app {
namespace {

constexpr double kFovDeg = 30.0;

// `s` holds the asset (id 1) and its materials: adds the entity showing
// it, a sun and the camera framing its bounding sphere.
scene::SceneState framed(scene::SceneState s, const mesh::MeshData& data) {
  PreviewRenderer::addStage(s);
  s.settings.meshLodErrorPixels = 0.0;  // the plant as generated
  scene::Entity e;
  e.id = 1;
  e.name = "Preview";
  e.mesh = scene::MeshInstance{1};
  s.entities.emplace(1, e);
  const mesh::Bounds b = data.bounds();
  const glm::dvec3 centre = b.empty ? glm::dvec3(0.0) : glm::dvec3(b.center());
  const double radius = std::max(b.empty ? 1.0 : double(b.radius()), 1e-3);
  const glm::dvec3 from = glm::normalize(glm::dvec3(-0.55, -0.8, 0.35));
  scene::Entity cam;
  cam.id = kPreviewCamera;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = kFovDeg;
  // The whole sphere in view, a little margin round it.
  const double distance = 1.08 * radius / std::sin(0.5 * kFovDeg * M_PI / 180.0);
  cam.camera->nearClip = std::max(1e-3, 0.01 * distance);
  cam.camera->farClip = 4.0 * distance;
  cam.transform.translation = centre + from * distance;
  cam.transform.rotation = sequencer::lookRotation(-from);
  s.entities.emplace(cam.id, cam);
  s.roots = {1, 2, kPreviewCamera};
  return s;
}

}  // namespace

std::optional<scene::SceneState> meshPreviewScene(const scene::SceneState& from, scene::AssetId asset) {
  const scene::MeshAsset* a = from.findAsset(asset);
  if (!a || !a->data) return std::nullopt;
  scene::SceneState s;
  scene::MeshAsset copy = *a;
  copy.id = 1;
  copy.lods.clear();
  for (scene::MaterialId m : copy.materialSlots)
    if (const scene::Material* mat = from.findMaterial(m)) {
      scene::Material mc = *mat;
      mc.asset = mat->asset == asset ? scene::AssetId(1) : mat->asset;
      for (scene::TextureId t : {mc.baseColorTexture, mc.normalMap, mc.heightMap})
        if (const scene::TextureAsset* ta = from.findTexture(t)) {
          scene::TextureAsset tc = *ta;
          if (tc.asset == asset) tc.asset = 1;
          s.textures.emplace(tc.id, tc);
        }
      s.materials.emplace(mc.id, mc);
    }
  const auto data = copy.data;
  s.assets.emplace(1, std::move(copy));
  return framed(std::move(s), *data);
}

std::optional<scene::SceneState> plantPreviewScene(const foliage::PlantParams& params, std::string& error) {
  mesh::MeshData m = foliage::generatePlant(params);
  if (m.triangleCount() == 0) {
    error = "the generator made no triangles from these parameters";
    return std::nullopt;
  }
  scene::SceneState s;
  scene::MeshAsset a;
  a.id = 1;
  a.name = "Plant preview";
  a.contentHash = mesh::contentHash(m);
  a.data = std::make_shared<const mesh::MeshData>(std::move(m));
  s.assets.emplace(1, a);
  scene::addMeshMaterials(s, 1);
  for (scene::MaterialId id : s.assets.at(1).materialSlots) scene::ops::applyPlantLook(s.materials.at(id));
  return framed(std::move(s), *a.data);
}

}  // namespace hs::app
