#include "app/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace hs::app {
namespace {

constexpr double kRadiansPerPixel = 0.0045;
constexpr double kMinPitch = glm::radians(0.5), kMaxPitch = glm::radians(179.5);
constexpr double kMinPivotDistance = 0.05;

}  // namespace

CameraController::CameraController() {
  view_.nearClip = 0.05;
  view_.farClip = 1.0e6;
  readAngles();
}

void CameraController::setView(const render::RenderView& v, double pivotDistance) {
  const int w = view_.width, h = view_.height;
  view_ = v;
  view_.width = w;
  view_.height = h;
  // The free view is no camera's, even when it starts where one stands: a
  // camera's own post settings show only through it (the stereo preview).
  view_.camera = scene::kNoEntity;
  // Reversed float depth keeps precision from a few cm to the far plane, so
  // the editor can afford a generous range whatever it was given.
  view_.nearClip = std::min(view_.nearClip, 0.05);
  view_.farClip = std::max(view_.farClip, 1.0e6);
  pivotDistance_ = std::max(pivotDistance, kMinPivotDistance);
  readAngles();
}

void CameraController::setViewportSize(int width, int height) {
  view_.width = std::max(width, 1);
  view_.height = std::max(height, 1);
}

void CameraController::frame(const scene::WorldBox& box) {
  if (box.empty) return;
  render::frameBoxKeepOrientation(view_, box.min, box.max);
  pivotDistance_ = std::max(glm::length(box.centre() - view_.eye), kMinPivotDistance);
  view_.nearClip = std::min(view_.nearClip, 0.05);
  view_.farClip = std::max(view_.farClip, 1.0e6);
  // A speed that crosses the framed object in about two seconds.
  flySpeed_ = std::clamp(pivotDistance_ * 0.5, 0.2, 5000.0);
}

void CameraController::readAngles() {
  const glm::dvec3 f = view_.forward();
  pitch_ = std::clamp(std::acos(std::clamp(-f.z, -1.0, 1.0)), kMinPitch, kMaxPitch);
  // Straight up or down the heading is undefined: take it from the up vector.
  const glm::dvec3 heading = std::hypot(f.x, f.y) > 1e-6 ? f : (f.z < 0 ? view_.up() : -view_.up());
  yaw_ = std::atan2(-heading.x, heading.y);
}

void CameraController::applyAngles() {
  pitch_ = std::clamp(pitch_, kMinPitch, kMaxPitch);
  view_.orientation = glm::angleAxis(yaw_, glm::dvec3(0, 0, 1)) * glm::angleAxis(pitch_, glm::dvec3(1, 0, 0));
}

void CameraController::beginFly() {
  flying_ = true;
  readAngles();
}

void CameraController::endFly() {
  flying_ = false;
  std::fill(std::begin(keys_), std::end(keys_), false);
  fast_ = false;
}

void CameraController::setMoveKey(MoveKey key, bool down) { keys_[key] = down; }

bool CameraController::moving() const {
  return flying_ && std::any_of(std::begin(keys_), std::end(keys_), [](bool k) { return k; });
}

bool CameraController::tick(double seconds) {
  if (!moving()) return false;
  glm::dvec3 dir(0.0);
  if (keys_[Forward]) dir += view_.forward();
  if (keys_[Back]) dir -= view_.forward();
  if (keys_[Right]) dir += view_.right();
  if (keys_[Left]) dir -= view_.right();
  if (keys_[Up]) dir.z += 1.0;
  if (keys_[Down]) dir.z -= 1.0;
  if (glm::length(dir) < 1e-9) return false;
  const double speed = flySpeed_ * (fast_ ? 4.0 : 1.0);
  view_.eye += glm::normalize(dir) * speed * std::min(seconds, 0.25);
  return true;
}

void CameraController::changeFlySpeed(double wheelSteps) {
  flySpeed_ = std::clamp(flySpeed_ * std::pow(1.25, wheelSteps), 0.01, 50000.0);
}

void CameraController::setFlySpeed(double metresPerSecond) {
  flySpeed_ = std::clamp(metresPerSecond, 0.01, 50000.0);
}

void CameraController::look(double dx, double dy) {
  yaw_ -= dx * kRadiansPerPixel;
  pitch_ -= dy * kRadiansPerPixel;
  applyAngles();
}

void CameraController::orbit(double dx, double dy) {
  const glm::dvec3 p = pivot();
  readAngles();
  yaw_ -= dx * kRadiansPerPixel;
  pitch_ -= dy * kRadiansPerPixel;
  applyAngles();
  view_.eye = p - view_.forward() * pivotDistance_;
}

void CameraController::pan(double dx, double dy) {
  const double metresPerPixel = view_.pixelSizeAt(pivotDistance_);
  view_.eye += (-view_.right() * dx + view_.up() * dy) * metresPerPixel;
}

void CameraController::dolly(double wheelSteps) {
  const double factor = std::pow(0.85, wheelSteps);
  const double next = pivotDistance_ * factor;
  if (next < kMinPivotDistance) {
    // Close to the pivot: push through it rather than stall.
    view_.eye += view_.forward() * (pivotDistance_ * 0.15 * wheelSteps);
    return;
  }
  const glm::dvec3 p = pivot();
  pivotDistance_ = next;
  view_.eye = p - view_.forward() * pivotDistance_;
}

void CameraController::dollyDrag(double dy) { dolly(-dy / 40.0); }

}  // namespace hs::app
