#include "render/render_view.h"

#include <cmath>

namespace hs::render {

glm::dmat4 RenderView::projection() const {
  const double f = 1.0 / std::tan(fovY * 0.5);
  const double n = nearClip, fa = std::max(farClip, nearClip * 1.0001);
  glm::dmat4 p(0.0);
  p[0][0] = f / aspect();
  p[1][1] = f;
  p[2][0] = -projectionShift.x;
  p[2][1] = -projectionShift.y;
  p[2][2] = n / (fa - n);
  p[2][3] = -1.0;
  p[3][2] = n * fa / (fa - n);
  return p;
}

void RenderView::pixelRay(double x, double y, glm::dvec3& origin, glm::dvec3& direction) const {
  // projection() adds the shift in NDC; undo it to get the view direction.
  const double ndcX = 2.0 * x / double(width) - 1.0 - projectionShift.x;
  const double ndcY = 1.0 - 2.0 * y / double(height) - projectionShift.y;
  const double t = std::tan(fovY * 0.5);
  const glm::dvec3 dirView(ndcX * t * aspect(), ndcY * t, -1.0);
  origin = eye;
  direction = glm::normalize(orientation * dirView);
}

bool RenderView::project(const glm::dvec3& world, glm::dvec2& pixel) const {
  const glm::dvec3 v = viewRotation() * (world - eye);
  if (v.z >= -1e-9) return false;
  const glm::dvec4 c = projection() * glm::dvec4(v, 1.0);
  const double ndcX = c.x / c.w, ndcY = c.y / c.w;
  pixel = {(ndcX + 1.0) * 0.5 * width, (1.0 - ndcY) * 0.5 * height};
  return true;
}

double RenderView::pixelSizeAt(double distance) const {
  return 2.0 * distance * std::tan(fovY * 0.5) / double(std::max(height, 1));
}

RenderView viewFromCamera(const scene::SceneState& state, scene::EntityId camera, int width, int height) {
  RenderView v;
  v.width = width;
  v.height = height;
  const scene::Entity* e = state.find(camera);
  if (!e) return v;
  const scene::Transform world = scene::Transform::fromMatrix(state.worldMatrix(camera));
  v.eye = world.translation;
  v.orientation = world.rotation;
  // A mirrored parent leaves a negative scale; the view ignores scale.
  if (e->camera) {
    v.fovY = glm::radians(e->camera->verticalFovDeg);
    v.nearClip = e->camera->nearClip;
    v.farClip = e->camera->farClip;
    v.lens = {true, e->camera->focusDistance, e->camera->fStop, e->name};
    v.camera = camera;
  }
  return v;
}

void frameBoxKeepOrientation(RenderView& v, const glm::dvec3& boxMin, const glm::dvec3& boxMax) {
  const glm::dvec3 centre = (boxMin + boxMax) * 0.5;
  const double radius = std::max(glm::length(boxMax - boxMin) * 0.5, 0.5);
  // Distance at which the bounding sphere fits the narrower field of view.
  const double halfFov = std::min(v.fovY, 2.0 * std::atan(std::tan(v.fovY * 0.5) * v.aspect())) * 0.5;
  const double distance = radius / std::sin(halfFov);
  v.eye = centre - v.forward() * distance;
  v.nearClip = std::max(distance * 1e-4, std::min(0.1, distance - radius));
  v.farClip = std::max(v.farClip, distance + radius * 4.0);
}

RenderView frameBox(const glm::dvec3& boxMin, const glm::dvec3& boxMax, int width, int height, double fovYDeg) {
  RenderView v;
  v.width = width;
  v.height = height;
  v.fovY = glm::radians(fovYDeg);
  // Look towards north-east (+x, +y), 25 degrees down: camera -Z must point
  // along that direction with +Y up (yaw about world Z, then pitch).
  const double yaw = glm::radians(-45.0), pitch = glm::radians(90.0 - 25.0);
  v.orientation = glm::angleAxis(yaw, glm::dvec3(0, 0, 1)) * glm::angleAxis(pitch, glm::dvec3(1, 0, 0));
  frameBoxKeepOrientation(v, boxMin, boxMax);
  return v;
}

Frustum frustumOf(const RenderView& view) {
  // Planes of clip space pulled back through projection * viewRotation
  // (Gribb-Hartmann), for the [0,1] reversed depth range.
  const glm::dmat4 m = view.projection() * glm::dmat4(view.viewRotation());
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  Frustum f;
  f.planes[0] = row(3) + row(0);  // left
  f.planes[1] = row(3) - row(0);  // right
  f.planes[2] = row(3) + row(1);  // bottom
  f.planes[3] = row(3) - row(1);  // top
  f.planes[4] = row(3) - row(2);  // near (depth <= 1)
  f.planes[5] = row(2);           // far (depth >= 0)
  for (auto& p : f.planes) p /= glm::length(glm::dvec3(p));
  return f;
}

bool Frustum::intersectsSphere(const glm::dvec3& c, double radius) const {
  for (const auto& p : planes)
    if (glm::dot(glm::dvec3(p), c) + p.w < -radius) return false;
  return true;
}

}  // namespace hs::render
