#include "app/material_preview.h"

#include "app/preview_renderer.h"
#include "mesh/primitives.h"
#include "scene/mesh_materials.h"
#include "sequencer/camera_path.h"

namespace hs::app {

MaterialPreview::MaterialPreview(int size, QObject* parent)
    : QObject(parent), renderer_(new PreviewRenderer(this)), size_(size) {
  connect(renderer_, &PreviewRenderer::ready, this, [this](int, const QImage& image) { emit ready(image); });
  connect(renderer_, &PreviewRenderer::problem, this,
          [this](const QString& message) { emit problem(QString(message).replace("Preview: ", "Material preview: ")); });
}

MaterialPreview::~MaterialPreview() = default;

scene::SceneState MaterialPreview::previewScene(const scene::SceneState& state, const scene::Material& material) {
  scene::SceneState s;
  PreviewRenderer::addStage(s);
  static const auto sphere = std::make_shared<const mesh::MeshData>(mesh::uvSphere(1.0f, 64, 32));
  scene::MeshAsset a;
  a.id = 1;
  a.name = "Preview";
  a.data = sphere;
  a.contentHash = 1;  // the same sphere every time: uploaded once
  scene::Material m = material;
  m.id = 1;
  m.asset = 1;
  // The material's textures, copied as standalone ones the preview keys by image.
  scene::TextureId next = 1;
  for (scene::TextureId* ref : {&m.baseColorTexture, &m.normalMap, &m.heightMap}) {
    const scene::TextureAsset* t = state.findTexture(*ref);
    if (!t) {
      *ref = scene::kNoTexture;
      continue;
    }
    scene::TextureAsset copy = *t;
    copy.id = next++;
    copy.asset = scene::kNoAsset;
    copy.meshTexture = -1;
    copy.srgb = ref == &m.baseColorTexture;
    copy.contentHash = reinterpret_cast<uintptr_t>(t->image.get()) ^ (t->contentHash * 31u);
    s.textures.emplace(copy.id, copy);
    *ref = copy.id;
  }
  a.materialSlots.assign(scene::materialSlotCount(*sphere), m.id);
  s.materials.emplace(m.id, m);
  s.assets.emplace(a.id, a);
  scene::Entity e;
  e.id = 1;
  e.name = "Preview";
  e.mesh = scene::MeshInstance{1};
  s.entities.emplace(1, e);
  scene::Entity cam;
  cam.id = kPreviewCamera;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 32.0;
  cam.camera->nearClip = 0.05;
  cam.transform.translation = {0.0, -3.8, 0.6};
  cam.transform.rotation = sequencer::lookRotation(-cam.transform.translation);
  s.entities.emplace(kPreviewCamera, cam);
  s.roots = {1, 2, kPreviewCamera};
  return s;
}

void MaterialPreview::request(const scene::SceneState& state, const scene::Material& material) {
  renderer_->request(0, previewScene(state, material), kPreviewCamera, size_);
}

}  // namespace hs::app
