#pragma once
// The Materials panel's preview: a sphere lit by a sun, rendered with one
// material on a worker thread with its own headless GL context (as the
// export does: the viewport's context stays with the UI thread). Requests
// replace each other (only the latest is rendered); the image comes back
// through ready() on the UI thread.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <QImage>
#include <QObject>

#include "scene/scene_state.h"

namespace hs::app {

class MaterialPreview : public QObject {
  Q_OBJECT
 public:
  explicit MaterialPreview(int size = 160, QObject* parent = nullptr);
  ~MaterialPreview() override;  // stops the worker (after the frame it is drawing)

  // Renders `material` (its textures taken from `state`) soon.
  void request(const scene::SceneState& state, const scene::Material& material);
  // The scene the worker renders for `material` (tests, and the worker itself).
  static scene::SceneState previewScene(const scene::SceneState& state, const scene::Material& material);

 signals:
  void ready(const QImage& image);
  // The worker could not start headless OpenGL, or the material's textures
  // could not be drawn (each problem names the material and field).
  void problem(const QString& message);

 private:
  void run();

  int size_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<scene::SceneState> pending_;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace hs::app
