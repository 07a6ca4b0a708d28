#pragma once
// Small still renders for the editor's previews (a material on a sphere, a
// plant, a foliage type's thumbnail), drawn on a worker thread with its own
// headless GL context (as the export does: the viewport's context stays
// with the UI thread). Each request carries a key; a newer request with
// the same key replaces one not yet drawn, so dragging a slider renders
// only the latest state. Images come back through ready() on the UI thread.
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include <QImage>
#include <QObject>

#include "scene/scene_state.h"

namespace hs::app {

// The previews' camera entity (PreviewRenderer::addStage has the sun at 2).
constexpr scene::EntityId kPreviewCamera = 3;

class PreviewRenderer : public QObject {
  Q_OBJECT
 public:
  explicit PreviewRenderer(QObject* parent = nullptr);
  ~PreviewRenderer() override;  // stops the worker (after the image it is drawing)

  // Renders `scene` from its camera entity `camera` at `size` x `size`
  // pixels soon (the worker's GL context starts with the first request).
  void request(int key, scene::SceneState scene, scene::EntityId camera, int size);

  // The previews' common stage: a neutral grey backdrop (no grid), FXAA,
  // a soft ambient and a sun (entity 2) turned (45, 0, -35) degrees.
  static void addStage(scene::SceneState& s);

 signals:
  void ready(int key, const QImage& image);
  // Headless OpenGL could not start, or the renderer refused part of the
  // scene (a material's textures): each message names what.
  void problem(const QString& message);

 private:
  struct Job {
    scene::SceneState scene;
    scene::EntityId camera = scene::kNoEntity;
    int size = 0;
  };
  void run();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<int, Job> pending_;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace hs::app
