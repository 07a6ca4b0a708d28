#pragma once
// The Materials panel's preview: a sphere lit by a sun, rendered with one
// material by a PreviewRenderer (its own GL context on a worker thread).
// Requests replace each other (only the latest is rendered); the image
// comes back through ready() on the UI thread.
#include <QImage>
#include <QObject>

#include "scene/scene_state.h"

namespace hs::app {

class PreviewRenderer;

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
  PreviewRenderer* renderer_;
  int size_;
};

}  // namespace hs::app
