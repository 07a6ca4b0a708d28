#pragma once
// The editor's stereo preview: the active camera's two eyes rendered at the
// size they take on screen and composed into the viewport's framebuffer as
// the left eye, the right eye, side by side, or a red/cyan anaglyph (the
// export's own Dubois composition, sequencer::composeLayout, so the preview
// shows the colours a film gets), letterboxed to the export's aspect. With a
// comfort budget it also reads the eyes' depth and checks the frame.
#include <optional>

#include "render/output_target.h"
#include "render/renderer.h"
#include "render/stereo_views.h"
#include "sequencer/camera_cuts.h"
#include "sequencer/comfort_check.h"

namespace hs::render {

enum class StereoPreviewMode { Left, Right, SideBySide, Anaglyph };

// A transition into `incoming` at this frame (sequencer::Shot).
struct PreviewTransition {
  scene::EntityId incoming = scene::kNoEntity;
  sequencer::Shot shot;
  int64_t frame = 0;
};

struct StereoPreviewResult {
  bool drawn = false;
  FrameStats stats;  // of the last eye rendered
  std::optional<sequencer::ComfortResult> comfort;
  int eyeWidth = 0, eyeHeight = 0;  // the size each eye was rendered at
};

class StereoPreviewRenderer {
 public:
  StereoPreviewRenderer() = default;
  StereoPreviewRenderer(const StereoPreviewRenderer&) = delete;
  StereoPreviewRenderer& operator=(const StereoPreviewRenderer&) = delete;

  // Draws the preview of `camera` in `state` into framebuffer `targetFbo` of
  // targetWidth x targetHeight, for frames of aspect `outputAspect` (eye
  // width / height of the export). Needs the renderer's context current.
  // With `transition` (a camera cut's transition at this frame), `camera`
  // is the outgoing shot and both are rendered and combined eye by eye as
  // the export combines them (two view groups); the comfort check reads
  // the stronger shot's depth.
  StereoPreviewResult draw(Renderer& renderer, const scene::SceneState& state, scene::EntityId camera,
                           StereoPreviewMode mode, double outputAspect, unsigned targetFbo, int targetWidth,
                           int targetHeight, const sequencer::ComfortOptions* comfort = nullptr,
                           const PreviewTransition* transition = nullptr);

  // Frees the GL objects (context current); no GL in the destructor.
  void release();

 private:
  struct Eye {
    OutputTarget target;
    OutputTarget groups[2];  // a transition's two shots, before they are combined
  };
  void ensureEyes(int width, int height);
  void ensureAnaglyph(int width, int height);

  Eye eyes_[2];
  unsigned anaglyphFbo_ = 0, anaglyphTexture_ = 0;
  int width_ = 0, height_ = 0;
  int anaglyphWidth_ = 0, anaglyphHeight_ = 0;
};

// The rectangle (x, y, width, height; origin bottom-left) of a picture of
// aspect `aspect` fitted, centred, into width x height.
struct FitRect {
  int x = 0, y = 0, width = 0, height = 0;
};
FitRect fitAspect(double aspect, int width, int height);

}  // namespace hs::render
