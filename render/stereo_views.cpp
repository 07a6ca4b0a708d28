#include "render/stereo_views.h"

#include <glm/gtc/matrix_transform.hpp>

namespace hs::render {

glm::mat4 windowToClip(const RenderView& a, const RenderView& b) {
  const glm::dmat4 toWorld = glm::translate(glm::dmat4(1.0), a.eye - b.eye) * glm::dmat4(glm::mat3_cast(a.orientation));
  return glm::mat4(b.projection() * glm::dmat4(b.viewRotation()) * toWorld * glm::inverse(a.projection()));
}

scene::EntityId shotCamera(const scene::SceneState& state) {
  const std::vector<scene::EntityId> cams = state.cameras();
  auto animated = [&](scene::EntityId id) {
    const sequencer::Binding* b = state.sequence.findBinding(id);
    return b && (b->path || !b->tracks.empty());
  };
  auto stereo = [&](scene::EntityId id) {
    const scene::Entity* e = state.find(id);
    return e && e->camera && e->camera->stereo != scene::Camera::Stereo::Mono;
  };
  // A stereo film's shot: an animated stereo rig first, then any animated
  // camera, then any stereo rig, then the first camera.
  for (auto want : {std::pair{true, true}, std::pair{true, false}, std::pair{false, true}})
    for (scene::EntityId id : cams)
      if ((!want.first || animated(id)) && (!want.second || stereo(id))) return id;
  return cams.empty() ? scene::kNoEntity : cams.front();
}

std::optional<sequencer::StereoRig> rigOf(const scene::Camera& c) {
  sequencer::StereoRig rig;
  switch (c.stereo) {
    case scene::Camera::Stereo::Mono: return std::nullopt;
    case scene::Camera::Stereo::OffAxis: rig.mode = sequencer::StereoMode::OffAxis; break;
    case scene::Camera::Stereo::Parallel: rig.mode = sequencer::StereoMode::Parallel; break;
    case scene::Camera::Stereo::ToeIn: rig.mode = sequencer::StereoMode::ToeIn; break;
  }
  switch (c.pivot) {
    case scene::Camera::Pivot::Left: rig.pivot = sequencer::RigPivot::Left; break;
    case scene::Camera::Pivot::Centre: rig.pivot = sequencer::RigPivot::Centre; break;
    case scene::Camera::Pivot::Right: rig.pivot = sequencer::RigPivot::Right; break;
  }
  rig.interaxial = c.interaxial;
  rig.convergence = c.convergence;
  return rig;
}

sequencer::CameraModel cameraModelOf(const RenderView& v) {
  sequencer::CameraModel m;
  m.position = v.eye;
  m.orientation = v.orientation;
  m.fovY = v.fovY;
  m.aspect = v.aspect();
  m.nearClip = v.nearClip;
  m.farClip = v.farClip;
  m.ndcShiftX = v.projectionShift.x;
  return m;
}

RenderView viewOfEye(const sequencer::CameraModel& eye, int width, int height) {
  RenderView v;
  v.width = width;
  v.height = height;
  v.eye = eye.position;
  v.orientation = eye.orientation;
  v.fovY = eye.fovY;
  v.nearClip = eye.nearClip;
  v.farClip = eye.farClip;
  v.projectionShift = {eye.ndcShiftX, 0.0};
  return v;
}

EyeViews eyeViews(const scene::SceneState& state, scene::EntityId camera, int width, int height) {
  EyeViews out;
  out.mono = viewFromCamera(state, camera, width, height);
  const sequencer::CameraModel mono = cameraModelOf(out.mono);
  const scene::Entity* e = state.find(camera);
  const std::optional<sequencer::StereoRig> rig = e && e->camera ? rigOf(*e->camera) : std::nullopt;
  if (!rig) {
    // Interaxial 0 gives two eyes equal to the mono camera (the comfort
    // check then sees zero parallax everywhere).
    out.eyes = sequencer::stereoCameras(mono, sequencer::StereoRig{sequencer::StereoMode::OffAxis, 0.0, 1.0});
    out.left = out.right = out.mono;
    return out;
  }
  out.stereo = true;
  out.eyes = sequencer::stereoCameras(mono, *rig);
  out.left = viewOfEye(out.eyes.left, width, height);
  out.right = viewOfEye(out.eyes.right, width, height);
  out.left.lens = out.right.lens = out.mono.lens;  // one focus for both eyes (depth of field)
  out.left.camera = out.right.camera = camera;     // and one post chain (the camera's overrides)
  return out;
}

}  // namespace hs::render
