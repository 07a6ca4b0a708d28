#include "render/auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/exposure_meter.h"
#include "render/output_target.h"
#include "render/renderer.h"
#include "scene/camera_post.h"
#include "scene/light_units.h"

namespace hs::render {

namespace {

ExposureMetering meteringOf(const scene::PostSettings& p) {
  return {.minEv100 = double(p.autoExposureMinEv100),
          .maxEv100 = double(p.autoExposureMaxEv100),
          .lowPercent = double(p.autoExposureLowPercent),
          .highPercent = double(p.autoExposureHighPercent),
          .compensationEv = double(p.autoExposureCompensation)};
}

ExposureAdaptation adaptationOf(const scene::PostSettings& p) {
  ExposureAdaptation a;
  a.speedUp = double(p.autoExposureSpeedUp);
  a.speedDown = double(p.autoExposureSpeedDown);
  a.probesPerSecond = double(p.autoExposureProbesPerSecond);
  return a;
}

// A probe's width: kProbeRows tall at the frame's aspect.
int probeWidth(double aspect) {
  constexpr int rows = AutoExposure::kProbeRows;
  return std::clamp(int(std::lround(rows * aspect)), 1, 16 * rows);
}

// The kept HDR is in scene units (before the exposure): back to cd/m².
ExposureHistogram histogramOf(const Image& hdr) {
  return luminanceHistogram(hdr.rgbaF.data(), hdr.pixelCount(), 1.0 / scene::sceneUnitsPerNit());
}

}  // namespace

double meteredEv100Of(const Image& hdr, const scene::PostSettings& post) {
  return meteredEv100(histogramOf(hdr), meteringOf(post));
}

scene::SceneState probeState(scene::SceneState state) {
  state.settings.post = scene::PostSettings{};
  state.settings.depthOfField = scene::DepthOfField::Off;
  state.settings.antialiasing = scene::Antialiasing::None;
  state.settings.showGrid = false;
  // What a mean over 72 rows cannot tell apart, made cheap: the smallest
  // sun shadow maps, no ambient occlusion, weighted blended transparency
  // (docs/rendering.md "Automatic exposure" gives the metering's change).
  state.settings.shadowQuality = scene::ShadowQuality::Low;
  state.settings.ao = scene::AmbientOcclusion::Off;
  state.settings.transparency = scene::Transparency::Weighted;
  return state;
}

struct AutoExposure::Impl {
  OutputTarget target;
  // Probes by (camera, the shot's start, the grid's step, probe width, grid
  // index): the histogram, so metering settings can change without renders.
  std::map<std::tuple<uint64_t, double, double, int, int64_t>, ExposureHistogram> probes;
  size_t rendered = 0;

  ExposureHistogram probe(Renderer& renderer, const scene::SceneState& state, RenderView view) {
    view.height = kProbeRows;
    view.lens = CameraLens{};
    view.camera = scene::kNoEntity;  // the probe's own settings, not the camera's post chain
    target.ensure(view.width, view.height);
    RenderOptions o;
    o.showGrid = false;
    o.keepHdr = true;
    renderer.render(probeState(state), view, target.fbo(), o);
    ++rendered;
    return histogramOf(renderer.readHdr(0));
  }

  double adapted(Renderer& renderer, const StateAtTime& stateAt, const scene::PostSettings& post,
                 scene::EntityId camera, double since, double seconds, double aspect) {
    const ExposureAdaptation a = adaptationOf(post);
    const ExposureMetering m = meteringOf(post);
    const double step = adaptationWindow(0.0, a).step;
    const int width = probeWidth(aspect);
    if (probes.size() > 4096) probes.clear();  // a long scrub: start again rather than grow
    return adaptedEv100(seconds - since, a, [&](int64_t g) {
      const auto key = std::make_tuple(uint64_t(camera), since, step, width, g);
      auto it = probes.find(key);
      if (it == probes.end()) {
        const double t = since + double(g) * step;
        const scene::SceneState state = stateAt(t);
        it = probes.emplace(key, probe(renderer, state, viewFromCamera(state, camera, width, kProbeRows))).first;
      }
      return meteredEv100(it->second, m);
    });
  }
};

AutoExposure::AutoExposure() : d_(std::make_unique<Impl>()) {}
AutoExposure::~AutoExposure() = default;

bool autoExposureOn(const scene::SceneState& frame, scene::EntityId camera,
                    const std::optional<sequencer::Shot>& shot) {
  const auto on = [&frame](uint64_t c) { return scene::settingsFor(frame, scene::EntityId(c)).post.autoExposure; };
  if (!shot) return on(camera);
  return on(shot->camera) || (shot->incoming && on(shot->incoming));
}

double AutoExposure::frameEv100(Renderer& renderer, const StateAtTime& stateAt, const scene::SceneState& frame,
                                scene::EntityId camera, const std::optional<sequencer::Shot>& shot,
                                sequencer::FrameRate rate, double seconds, double aspect) {
  // One camera's: its settings say whether and how to meter.
  const auto exposureOf = [&](scene::EntityId c, double since) {
    const scene::SceneSettings s = scene::settingsFor(frame, c);
    return s.post.autoExposure ? d_->adapted(renderer, stateAt, s.post, c, since, seconds, aspect)
                               : double(s.exposureEv100);
  };
  if (!shot) return exposureOf(camera, 0.0);
  const double outgoing =
      exposureOf(scene::EntityId(shot->camera), sequencer::frameTime(shot->cameraSince, rate));
  if (!shot->incoming) return outgoing;
  const double incoming =
      exposureOf(scene::EntityId(shot->incoming), sequencer::frameTime(shot->incomingSince, rate));
  return outgoing + (incoming - outgoing) * std::clamp(shot->progress, 0.0, 1.0);
}

double AutoExposure::viewEv100(Renderer& renderer, const scene::SceneState& state, const RenderView& view) {
  const scene::SceneSettings settings = scene::settingsFor(state, view.camera);
  if (!settings.post.autoExposure) return double(settings.exposureEv100);
  RenderView v = view;
  v.width = probeWidth(view.aspect());
  return meteredEv100(d_->probe(renderer, state, v), meteringOf(settings.post));
}

size_t AutoExposure::probesRendered() const { return d_->rendered; }

void AutoExposure::forget() { d_->probes.clear(); }

void AutoExposure::release() {
  d_->target.release();
  forget();
}

}  // namespace hs::render
