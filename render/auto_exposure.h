#pragma once
// Automatic exposure of frames (PostSettings::autoExposure; docs/rendering.md
// "Automatic exposure"). A frame's exposure is metered from small probe
// renders of its shot, each the scene as it is at a time of a fixed grid
// from the shot's start (the state that time gives: the same pure function
// the frame comes from), through a luminance histogram, and adapted over
// them as core/exposure_meter.h says. Nothing depends on the frame drawn
// before, so a frame exported alone, in a farm chunk or in a whole sequence
// gets the same exposure; probes are kept by camera and time, so a sequence
// renders each once (probes_per_second of them per second of film), a
// frame alone its window's worth. Both eyes share the exposure (one mono
// probe), so they never differ in brightness.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "core/image.h"
#include "render/render_view.h"
#include "scene/scene_state.h"
#include "sequencer/camera_cuts.h"
#include "sequencer/frame_range.h"

namespace hs::render {

class Renderer;

// The scene at a time (scene::animatedState of the document).
using StateAtTime = std::function<scene::SceneState(double seconds)>;

// True where the frame through `camera` (or `shot`'s cameras) meters its
// exposure: post.auto_exposure on in the scene's settings or a camera's.
bool autoExposureOn(const scene::SceneState& frame, scene::EntityId camera,
                    const std::optional<sequencer::Shot>& shot);

class AutoExposure {
 public:
  AutoExposure();
  ~AutoExposure();
  AutoExposure(const AutoExposure&) = delete;
  AutoExposure& operator=(const AutoExposure&) = delete;

  // The EV100 the frame at `seconds` renders with through `camera` (or,
  // with `shot`, through the shot's camera, or its two cameras during a
  // transition: their exposures mixed by its progress): adapted where the
  // camera's settings (the scene's, with its overrides:
  // scene/camera_post.h) have post.auto_exposure on, their manual
  // exposure_ev100 where off. `frame` is the state at `seconds`;
  // `rate` turns the cuts' frames into times; `aspect` is the frame's
  // width / height. Renders probes it does not have: call between frames,
  // with the renderer's context current.
  double frameEv100(Renderer& renderer, const StateAtTime& stateAt, const scene::SceneState& frame,
                    scene::EntityId camera, const std::optional<sequencer::Shot>& shot, sequencer::FrameRate rate, double seconds,
                    double aspect);
  // The EV100 metered from one probe of `view` of `state`, no adaptation:
  // a view that is no camera's (a CLI still framing the scene) has no
  // history. (The editor's free view meters what it drew: meteredEv100Of.)
  double viewEv100(Renderer& renderer, const scene::SceneState& state, const RenderView& view);

  // Probes rendered since the start (tests, benchmarks, the status bar).
  size_t probesRendered() const;
  // The scene changed: forget every probe.
  void forget();
  // Frees the probe's framebuffer (the context current).
  void release();

  // Probe size: this many rows, as wide as the frame's aspect asks.
  static constexpr int kProbeRows = 72;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

// The EV100 metered from `hdr`, a frame's linear HDR as Renderer::readHdr
// gives it (scene units, before the exposure), by `post`'s metering
// settings: the editor's free view meters the picture it drew.
double meteredEv100Of(const Image& hdr, const scene::PostSettings& post);

// The state a probe renders: `state` with its post chain, depth of field
// and anti-aliasing off and cheaper shadows, AO and transparency (tests
// meter the same way).
scene::SceneState probeState(scene::SceneState state);

}  // namespace hs::render
