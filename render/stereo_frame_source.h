#pragma once
// The export's renderer: a sequencer::FrameSource over an OffscreenRenderer.
// For frame N it evaluates the scene at t = frame time
// (scene::animatedState, a pure function), looks through the camera, renders
// the rig's two eyes (or the mono view) and queues their readback into pixel
// buffers; the pixels are mapped one frame later, so the GPU draws frame
// N+1 while frame N travels back (two frames in flight) and an export costs
// little more than its rendering. A frame's pixels depend only on the scene
// and t, never on the frames before it: frame 30,000 of a run is byte for
// byte frame 30,000 of a farm chunk that starts there.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/offscreen_renderer.h"
#include "scene/scene_state.h"
#include "sequencer/comfort_check.h"
#include "sequencer/export_loop.h"

namespace hs::render {

struct StereoFrameOptions {
  // kNoEntity: the scene's camera cuts (sequencer/camera_cuts.h) choose each
  // frame's camera, a transition's frames render both shots as two view
  // groups combined (Renderer::renderGroups); frames outside every cut,
  // and scenes without cuts, look through shotCamera(). A camera named
  // here is used for every frame, cuts or not.
  scene::EntityId camera = scene::kNoEntity;
  bool showGrid = true;          // AND-ed with the scene's own grid setting, as for a single frame
  // Display pixels at 16 bits (for 16-bit PNG), handed over as linear float
  // so layouts and the writer keep the precision. Without FXAA only: its
  // intermediate buffer is 8-bit.
  bool displayBits16 = false;
  // Read the eyes' depth and check each frame's parallax against the budget.
  // Off by default: a frame that does not need its depth never reads it.
  std::optional<sequencer::ComfortOptions> comfort;
  int framesInFlight = 2;        // 1: read back each frame before starting the next
};

class StereoFrameSource final : public sequencer::FrameSource {
 public:
  // `renderer` must be initialized; its context is made current on every
  // call, from the thread that runs the export.
  StereoFrameSource(OffscreenRenderer& renderer, const scene::SceneState& scene, const StereoFrameOptions& options);
  ~StereoFrameSource() override;

  bool begin(const sequencer::FrameJob& job, std::string& error) override;
  bool finish(const sequencer::FrameJob& job, sequencer::EyeImages& out, std::string& error) override;
  int framesInFlight() const override;

  // The camera of frames outside every cut (or of every frame without cuts).
  scene::EntityId camera() const;
  // Per finished frame, in order, when options.comfort is set.
  const std::vector<sequencer::FrameComfort>& comfort() const;
  std::function<void(const sequencer::FrameComfort&)> onComfort;
  // What the timeline could not apply (a track for a missing entity, an aim
  // target not found), each message once.
  const std::vector<std::string>& warnings() const;
  // Time the GPU was waited for while mapping pixel buffers (the part of
  // readback that did not overlap rendering), seconds.
  double readbackWaitSeconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace hs::render
