#pragma once
// The editor camera: a double-precision RenderView moved by fly (right mouse
// + WASD/QE) and orbit/pan/dolly (Alt + mouse) controls. Qt-free maths so the
// same behaviour can be unit-tested; the viewport feeds it input.
#include "render/render_view.h"
#include "scene/world_bounds.h"

namespace hs::app {

class CameraController {
 public:
  enum MoveKey { Forward, Back, Left, Right, Up, Down, kMoveKeyCount };

  CameraController();

  const render::RenderView& view() const { return view_; }
  // Takes `v` (its size is replaced by the viewport's); the orbit pivot is
  // `pivotDistance` ahead of the eye.
  void setView(const render::RenderView& v, double pivotDistance);
  void setViewportSize(int width, int height);
  glm::dvec3 pivot() const { return view_.eye + view_.forward() * pivotDistance_; }
  double pivotDistance() const { return pivotDistance_; }

  // Moves the eye (orientation kept) so the box fills the view, and puts the
  // pivot at its centre.
  void frame(const scene::WorldBox& box);

  // Fly mode.
  void beginFly();
  void endFly();
  bool flying() const { return flying_; }
  void setMoveKey(MoveKey key, bool down);
  void setFast(bool fast) { fast_ = fast; }
  bool moving() const;
  // Integrates movement for `seconds` of held keys. Returns whether it moved.
  bool tick(double seconds);
  void changeFlySpeed(double wheelSteps);
  double flySpeed() const { return flySpeed_; }
  void setFlySpeed(double metresPerSecond);

  // Mouse deltas in pixels.
  void look(double dx, double dy);    // turn in place (fly)
  void orbit(double dx, double dy);   // around the pivot
  void pan(double dx, double dy);     // slide eye and pivot in the view plane
  void dolly(double wheelSteps);      // towards (+) / away from (-) the pivot
  void dollyDrag(double dy);

 private:
  void readAngles();
  void applyAngles();

  render::RenderView view_;
  double pivotDistance_ = 10.0;
  double yaw_ = 0.0, pitch_ = 0.0;  // radians; pitch 0 looks straight down, pi straight up
  bool flying_ = false;
  bool fast_ = false;
  bool keys_[kMoveKeyCount] = {};
  double flySpeed_ = 5.0;  // m/s
};

}  // namespace hs::app
