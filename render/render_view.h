#pragma once
// A viewpoint in double precision and the camera-relative maths built on it.
// No GL here: the editor's picking and gizmos use it too.
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/scene_state.h"

namespace hs::render {

// The lens of the camera a view is taken from, for depth of field
// (render/dof_lens.h). A view that is no camera's (the editor's free view)
// has none and is never blurred.
struct CameraLens {
  bool present = false;
  double focusDistance = 10.0;  // metres (Camera::focusDistance)
  double fStop = 8.0;           // Camera::fStop
  std::string camera;           // the camera entity's name, for messages
};

struct RenderView {
  glm::dvec3 eye{0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // camera to world; looks down -Z, +Y up
  double fovY = glm::radians(50.0);            // vertical, radians
  double nearClip = 0.1;
  double farClip = 50000.0;
  int width = 1;
  int height = 1;
  glm::dvec2 projectionShift{0.0};  // NDC offset (off-axis frusta)
  CameraLens lens;                  // depth of field; both eyes of a pair share the camera's
  // The camera entity the view is taken from: its own post settings apply
  // (scene/camera_post.h). kNoEntity for a view that is no camera's.
  scene::EntityId camera = scene::kNoEntity;

  double aspect() const { return double(width) / double(std::max(height, 1)); }
  glm::dvec3 forward() const { return orientation * glm::dvec3(0, 0, -1); }
  glm::dvec3 right() const { return orientation * glm::dvec3(1, 0, 0); }
  glm::dvec3 up() const { return orientation * glm::dvec3(0, 1, 0); }
  // World to view rotation (no translation: positions are camera-relative).
  glm::dmat3 viewRotation() const { return glm::mat3_cast(glm::conjugate(orientation)); }
  // Reversed-Z projection for a [0,1] depth range: 1 at the near plane, 0 at
  // the far plane, so a float depth buffer keeps precision to tens of km.
  glm::dmat4 projection() const;

  // Ray through window pixel (x, y), origin top-left, pixel centres at +0.5.
  void pixelRay(double x, double y, glm::dvec3& origin, glm::dvec3& direction) const;
  // World point to window pixel (origin top-left). False if behind the camera.
  bool project(const glm::dvec3& world, glm::dvec2& pixel) const;
  // World-space size of one pixel at `distance` along the view direction.
  double pixelSizeAt(double distance) const;
};

// The view through a camera entity (its world transform and Camera
// component). Scale in the transform is ignored.
RenderView viewFromCamera(const scene::SceneState& state, scene::EntityId camera, int width, int height);

// A view that frames `box` (a world box, see scene/world_bounds.h): looking
// at its centre from the south-west and above, far enough to see all of it.
RenderView frameBox(const glm::dvec3& boxMin, const glm::dvec3& boxMax, int width, int height,
                    double fovYDeg = 50.0);
// Moves `view` (keeping its orientation) so the box fills the view.
void frameBoxKeepOrientation(RenderView& view, const glm::dvec3& boxMin, const glm::dvec3& boxMax);

// Six planes (inward normals, camera-relative) for culling bounding spheres.
struct Frustum {
  glm::dvec4 planes[6];
  // Sphere centre relative to the eye.
  bool intersectsSphere(const glm::dvec3& centreRel, double radius) const;
};
Frustum frustumOf(const RenderView& view);

}  // namespace hs::render
