#include <chrono>
#include <cstdio>

#include "cli/commands.h"
#include "cli/render_frames.h"
#include "cli/scene_open.h"
#include "cli/sequence_options.h"
#include <fstream>

#include "render/auto_exposure.h"
#include "render/frame_stats_json.h"
#include "render/offscreen_renderer.h"
#include "render/render_problems.h"
#include "scene/animation.h"
#include "scene/camera_cuts_check.h"
#include "scene/hscene_file.h"
#include "scene/render_operation.h"
#include "scene/world_bounds.h"
#include "sequencer/camera_cuts.h"
#include "sequencer/frame_range.h"
#include "sequencer/image_writer.h"

namespace hs::cli {

int runRender(int argc, char** argv) {
  OperationArgs args(scene::renderOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  // Any sequence option (--frames, --layout, --video, ...) makes it a sequence render.
  if (isSequenceRender(args)) {
    if (args.has("stats")) return args.usage("--stats applies to one frame, not a sequence");
    if (args.has("time_s")) return args.usage("--at applies to one frame; a sequence's frames have their own times");
    if (args.has("mix_camera") || args.has("mix_transition"))
      return args.usage("--mix-camera and --transition apply to one frame (a sequence's cuts and transitions come from its timeline)");
    return renderFrames(args);
  }
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  if (!args.has("out")) return args.usage("--out FILE is required");
  const std::string out = args.text("out");
  const auto format = sequencer::imageFormatFromPath(out);
  if (!format) return args.fail(out + ": unknown image type; use .png, .exr, .jpg or .tif");
  int width = 1920, height = 1080;
  eyeSizeOf(args, width, height);
  sequencer::WriteOptions writeOptions;
  writeOptions.jpegQuality = int(args.integer("quality"));

  std::string error;
  std::optional<scene::SceneState> state = openScene(args.positionals()[0], error);
  if (!state) return args.fail(error);
  // The document as opened and its timeline: automatic exposure's probes
  // evaluate it at the times before --at.
  std::optional<scene::SceneState> document;
  std::optional<sequencer::CompiledSequence> compiled;
  if (args.has("time_s")) {
    // The timeline at t: what a sequence render's frame at t sees (scene::animatedState).
    std::vector<std::string> warnings;
    document = *state;
    compiled = scene::compileSequence(*document);
    *state = scene::animatedState(*document, *compiled, args.number("time_s"), &warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  applyAntialiasing(args, *state);
  if (args.has("mix_transition") && !args.has("mix_camera"))
    return args.usage("--transition draws a transition into --mix-camera's shot: give --mix-camera too");

  // A camera by name, or why there is none.
  auto namedCamera = [&](const std::string& name, std::string& why) -> scene::EntityId {
    const scene::EntityId id = state->findByName(name);
    if (id != scene::kNoEntity && state->find(id)->camera) return id;
    std::string known;
    for (scene::EntityId c : state->cameras()) known += (known.empty() ? "" : ", ") + ("'" + state->find(c)->name + "'");
    why = "no camera named '" + name + "' in " + args.positionals()[0] +
          (known.empty() ? " (it has no cameras)" : " (cameras: " + known + ")");
    return scene::kNoEntity;
  };
  // With --at and no --camera, the timeline's camera cuts choose the shot at
  // that frame, as a sequence's frame would (a transition: both shots).
  std::optional<sequencer::Shot> cut;
  if (!args.has("camera") && args.has("time_s") && !state->sequence.cuts.empty()) {
    if (const std::string problem = scene::cutsProblem(*state); !problem.empty())
      return args.fail(args.positionals()[0] + ": the camera cuts cannot be rendered: " + problem +
                       " (name a camera with --camera)");
    cut = sequencer::shotAt(state->sequence.cuts, sequencer::frameAtTime(args.number("time_s"), state->sequence.rate));
  }
  render::RenderView view;
  std::string from;
  scene::EntityId viewCamera = scene::kNoEntity;  // none: a view framing the scene
  if (args.has("camera")) {
    const std::string name = args.text("camera");
    viewCamera = namedCamera(name, error);
    if (viewCamera == scene::kNoEntity) return args.fail(error);
    from = "camera '" + name + "'";
  } else if (cut) {
    viewCamera = scene::EntityId(cut->camera);
    from = "camera '" + state->find(viewCamera)->name + "' (the camera cuts)";
  } else if (const auto cams = state->cameras(); !cams.empty()) {
    viewCamera = cams.front();
    from = "camera '" + state->find(viewCamera)->name + "'";
  } else {
    const scene::WorldBox box = scene::worldBounds(*state);
    view = render::frameBox(box.empty ? glm::dvec3(-5) : box.min, box.empty ? glm::dvec3(5) : box.max, width, height);
    from = "a view framing the scene";
  }
  if (viewCamera != scene::kNoEntity) view = render::viewFromCamera(*state, viewCamera, width, height);
  scene::EntityId mixCamera = scene::kNoEntity;
  if (args.has("mix_camera")) {
    mixCamera = namedCamera(args.text("mix_camera"), error);
    if (mixCamera == scene::kNoEntity) return args.fail(error);
  }
  // The timeline's frame at --at (it seeds the glitch's pattern).
  const int64_t frame = args.has("time_s") ? sequencer::frameAtTime(args.number("time_s"), state->sequence.rate) : 0;
  // The shot: the cuts' at --at, or --mix-camera's two at progress --mix
  // (combined by --transition's pattern, or crossfaded).
  std::optional<sequencer::Shot> shot = cut;
  if (mixCamera != scene::kNoEntity)
    shot = sequencer::Shot{viewCamera, mixCamera,
                           sequencer::transitionFromName(args.text("mix_transition")).value_or(sequencer::Transition::Crossfade),
                           args.number("mix")};

  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) return args.fail("cannot start headless OpenGL: " + error);
  const auto t0 = std::chrono::steady_clock::now();
  render::FrameStats stats;
  render::RenderOptions options;
  options.showGrid = !args.flag("no_grid");
  // Per-pass GPU timestamps wait for the GPU: only when they are asked for.
  options.passTimings = args.has("stats");
  options.oitCounts = args.has("stats");  // fragments per pixel in every transparency mode
  const bool hdr = *format == sequencer::ImageFormat::Exr;
  if (render::autoExposureOn(*state, viewCamera, shot)) {
    // Metered from probes of the shot before --at as a sequence's frame
    // (render/auto_exposure.h); a view of no camera from its one probe.
    render::AutoExposure exposure;
    const render::StateAtTime stateAt = [&](double t) {
      return document ? scene::animatedState(*document, *compiled, t, nullptr) : *state;
    };
    const double ev = viewCamera == scene::kNoEntity
                          ? exposure.viewEv100(renderer.renderer(), *state, view)
                          : exposure.frameEv100(renderer.renderer(), stateAt, *state, viewCamera, shot,
                                                state->sequence.rate, args.has("time_s") ? args.number("time_s") : 0.0,
                                                double(width) / double(height));
    exposure.release();
    state->settings.exposureEv100 = float(ev);
    char text[96];
    std::snprintf(text, sizeof text, ", automatic exposure EV100 %.2f (%zu probes)", ev, exposure.probesRendered());
    from += text;
  }
  hs::Image img;
  if (shot && shot->incoming) {
    // Two shots in one frame (Renderer::renderGroups), combined as a
    // sequence's transition frame is.
    const render::GroupCombine pattern = render::combineOf(*shot, frame);
    const scene::EntityId incoming(shot->incoming);
    img = renderer.renderMix(*state, {view, render::viewFromCamera(*state, incoming, width, height)}, pattern.weights,
                             hdr, &stats, options, &pattern);
    const std::string progress = std::to_string(shot->progress).substr(0, 4);
    if (mixCamera != scene::kNoEntity)
      from += " mixed with camera '" + args.text("mix_camera") + "' (" + args.text("mix_transition") + " at " +
              progress + ")";
    else
      from += " in a " + std::string(sequencer::transitionName(shot->transition)) + " into camera '" +
              state->find(incoming)->name + "' (" + progress + ")";
  } else {
    img = renderer.render(*state, view, hdr, &stats, options);
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& p : render::takeRenderProblems(renderer.renderer()))
    std::fprintf(stderr, "warning: %s\n", p.c_str());
  hs::ImageView iv{img.width, img.height, img.rgba8.empty() ? nullptr : img.rgba8.data(),
                          img.rgbaF.empty() ? nullptr : img.rgbaF.data()};
  if (!sequencer::writeImage(out, iv, error, writeOptions)) return args.fail(error);
  if (args.has("stats")) {
    const std::string statsPath = args.text("stats");
    std::ofstream file(statsPath);
    file << writeJson(render::frameStatsJson(stats, renderer.renderer().resourceRegistry())) << "\n";
    if (!file) return args.fail(statsPath + ": cannot write the statistics");
  }
  std::printf("rendered %dx%d from %s: %zu triangles, %zu draw calls, %.1f ms (%s) -> %s\n", width, height,
              from.c_str(), stats.trianglesDrawn, stats.drawCalls, ms, renderer.glDescription().c_str(), out.c_str());
  return 0;
}

}  // namespace hs::cli
