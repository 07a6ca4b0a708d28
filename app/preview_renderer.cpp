#include "app/preview_renderer.h"

#include <cstring>

#include "render/offscreen_renderer.h"
#include "render/render_view.h"

namespace hs::app {

PreviewRenderer::PreviewRenderer(QObject* parent) : QObject(parent) {
  worker_ = std::thread([this] { run(); });
}

PreviewRenderer::~PreviewRenderer() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void PreviewRenderer::request(int key, scene::SceneState scene, scene::EntityId camera, int size) {
  {
    std::lock_guard lock(mutex_);
    pending_[key] = Job{std::move(scene), camera, size};
  }
  wake_.notify_all();
}

void PreviewRenderer::addStage(scene::SceneState& s) {
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::Fxaa;
  s.settings.skyZenith = s.settings.skyHorizon = glm::vec3(0.16f, 0.17f, 0.19f);
  s.settings.groundColor = glm::vec3(0.1f);
  s.settings.ambientIntensity = 0.6f;
  scene::Entity sun;
  sun.id = 2;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({45, 0, -35});
  s.entities.emplace(2, sun);
}

void PreviewRenderer::run() {
  std::unique_ptr<render::OffscreenRenderer> renderer;
  for (;;) {
    int key = 0;
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !pending_.empty(); });
      if (stop_) break;
      auto it = pending_.begin();
      key = it->first;
      job = std::move(it->second);
      pending_.erase(it);
    }
    if (!renderer) {
      renderer = std::make_unique<render::OffscreenRenderer>();
      std::string error;
      if (!renderer->initialize(error)) {
        QMetaObject::invokeMethod(
            this, [this, e = QString::fromStdString(error)] { emit problem("Preview: " + e); }, Qt::QueuedConnection);
        renderer.reset();
        continue;
      }
    }
    const render::RenderView view = render::viewFromCamera(job.scene, job.camera, job.size, job.size);
    const hs::Image img = renderer->render(job.scene, view);
    QImage out(img.width, img.height, QImage::Format_RGBA8888);
    for (int y = 0; y < img.height; ++y)
      std::memcpy(out.scanLine(y), img.rgba8.data() + size_t(y) * size_t(img.width) * 4, size_t(img.width) * 4);
    std::vector<std::string> problems = renderer->renderer().takeMaterialProblems();
    QMetaObject::invokeMethod(
        this,
        [this, key, out, problems] {
          emit ready(key, out);
          for (const auto& p : problems) emit problem(QString::fromStdString(p));
        },
        Qt::QueuedConnection);
    // A preview's assets are not kept: the next request brings its own.
    renderer->renderer().collectGarbage(job.scene);
  }
  if (renderer) renderer->renderer().shutdown();
}

}  // namespace hs::app
