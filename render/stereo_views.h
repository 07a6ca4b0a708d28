#pragma once
// From a camera entity to the views a stereo frame renders: the camera's
// own (mono) view and its rig's two eyes, through sequencer::stereoCameras()
// (off-axis shift copied into RenderView::projectionShift.x). No GL: the
// export's frame source, the editor's stereo preview and its comfort
// readout all start here, so they frame a shot the same way.
#include <string>
#include <vector>

#include "render/render_view.h"
#include "scene/scene_state.h"
#include "sequencer/stereo_rig.h"

namespace hs::render {

// The camera a sequence renders through when none is named, in outliner
// order: the first stereo camera the timeline animates (tracks or a path),
// else the first animated camera, else the first stereo camera, else the
// first camera; kNoEntity if the scene has none.
scene::EntityId shotCamera(const scene::SceneState& state);

// The rig of a camera component; nullopt for a mono camera.
std::optional<sequencer::StereoRig> rigOf(const scene::Camera& camera);

struct EyeViews {
  RenderView mono;           // the camera itself
  RenderView left, right;    // the eyes; both equal `mono` for a mono camera
  bool stereo = false;       // the camera has a stereo rig
  sequencer::StereoCameras eyes;  // the rig maths' eyes (for the comfort check)
};

// The views of `camera` in `state` (an animated state for a frame) for eyes
// of width x height. A mono camera gives three equal views.
EyeViews eyeViews(const scene::SceneState& state, scene::EntityId camera, int width, int height);

sequencer::CameraModel cameraModelOf(const RenderView& view);

// From view `a`'s window coordinates (x, y in NDC, z its reversed-Z depth)
// to view `b`'s clip space: a's inverse projection, the views' rotations
// and the offset between their eyes, b's projection, composed in double
// (positions are camera-relative; the offset is small). The stylised
// effects that attach one eye's pattern to the other's surfaces
// (stippling, error diffusion) reproject with it.
glm::mat4 windowToClip(const RenderView& a, const RenderView& b);
// A view from an eye camera of the rig (position, orientation, NDC shift).
RenderView viewOfEye(const sequencer::CameraModel& eye, int width, int height);

}  // namespace hs::render
