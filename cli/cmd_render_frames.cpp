#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <unistd.h>

#include "cli/commands.h"
#include "cli/render_frames.h"
#include "cli/scene_open.h"
#include "cli/sequence_options.h"
#include "render/export_job_tag.h"
#include "render/offscreen_renderer.h"
#include "render/render_problems.h"
#include "render/stereo_frame_source.h"
#include "scene/camera_cuts_check.h"
#include "scene/hscene_file.h"
#include "sequencer/ffmpeg_writer.h"

namespace hs::cli {

namespace {

// Ctrl-C cancels the export through it (Progress::cancel is signal-safe).
Progress gInterrupted;

// Ctrl-C stops after the frames already rendered are written (they are
// whole files; running again resumes). A second Ctrl-C ends at once.
void onInterrupt(int) {
  gInterrupted.cancel();
  std::signal(SIGINT, SIG_DFL);
}

std::string percent(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.2f%%", share * 100.0);
  return buf;
}

std::string metres(double d) {
  if (!std::isfinite(d)) return "infinity (sky)";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f m", d);
  return buf;
}

// Progress on stderr: a line rewritten in place on a terminal; in a log
// (a farm task's) a line every 10 s, so short runs print none.
class ProgressPrinter {
 public:
  void operator()(const sequencer::ExportProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    const bool done = p.written + p.kept >= p.total;
    if (!tty_ && !done && now - last_ < std::chrono::seconds(10)) return;
    if (!tty_ && done && !printedAny_) return;
    if (done && printedDone_) return;
    printedDone_ = done;
    last_ = now;
    printedAny_ = true;
    std::string eta = p.etaSeconds >= 0.0 ? formatDuration(p.etaSeconds) : std::string("?");
    std::fprintf(stderr, "%sframe %lld: %lld/%lld done (%lld kept), %.2f fps, elapsed %s, ETA %s%s",
                 tty_ ? "\r" : "", static_cast<long long>(p.lastFrame), static_cast<long long>(p.written + p.kept),
                 static_cast<long long>(p.total), static_cast<long long>(p.kept), p.framesPerSecond,
                 formatDuration(p.elapsedSeconds).c_str(), eta.c_str(), tty_ ? "   " : "\n");
    std::fflush(stderr);
  }
  void end() {
    if (tty_ && printedAny_) std::fprintf(stderr, "\n");
  }

 private:
  bool tty_ = isatty(STDERR_FILENO);
  bool printedAny_ = false;
  bool printedDone_ = false;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

int renderFrames(const OperationArgs& args) {
  std::string error;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string scenePath = args.positionals()[0];

  sequencer::ExportSettings s;
  s.layout = layoutOf(args);
  eyeSizeOf(args, s.eyeWidth, s.eyeHeight);
  const bool hasOut = args.has("out"), hasVideo = args.has("video");
  if (hasOut && hasVideo) return args.usage("give --out PATTERN for frames or --video FILE for a film, not both");
  if (!hasOut && !hasVideo) return args.usage("--out PATTERN (frame files) or --video FILE (a film) is required");
  s.output = hasVideo ? args.text("video") : args.text("out");
  const bool film = sequencer::videoContainerFromPath(s.output).has_value();
  if (hasVideo && !film) return args.fail(s.output + ": a film must end in .mp4 or .mkv");
  if (!film && !sequencer::imageFormatFromPath(s.output))
    return args.fail(s.output + ": unknown image type; use .png, .exr, .jpg, .tif, or .mp4 / .mkv for a film");
  if (film && s.layout == sequencer::StereoLayout::Separate)
    return args.fail(s.output + ": a film holds one picture a frame, not --layout separate; use sbs, tb or "
                     "another single-image layout");
  s.video.codec = args.text("codec") == "h265" ? sequencer::VideoCodec::H265 : sequencer::VideoCodec::H264;
  s.video.crf = int(args.integer("crf"));
  s.image.jpegQuality = int(args.integer("quality"));
  s.writerThreads = int(args.integer("writers"));
  s.video.preset = args.text("preset");
  s.image.png16 = args.flag("png16");
  if (s.image.png16 && sequencer::imageFormatFromPath(s.output) != sequencer::ImageFormat::Png)
    return args.usage("--png16 needs a .png output");
  s.resume = !args.flag("overwrite");
  sequencer::ComfortBudget budget;
  budgetOf(args, budget);

  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  applyAntialiasing(args, *state);
  if (args.has("fps")) {
    const auto rate = sequencer::parseFrameRate(args.text("fps"), error);
    if (!rate) return args.usage("--fps: " + error);
    state->sequence.rate = *rate;
  }
  s.rate = state->sequence.rate;
  if (!parseFrames(args, &*state, s.frames, error)) return args.usage(error);
  if (s.frames.empty()) return args.fail("no frames to render");
  const scene::EntityId camera = findCamera(*state, args.text("camera"), scenePath, error);
  if (camera == scene::kNoEntity) return args.fail(error);
  const scene::Entity& cam = *state->find(camera);
  if (film && !sequencer::ffmpegAvailable(s.video.ffmpeg))
    return args.fail(s.output + ": direct video needs ffmpeg, which is not installed (apt-get install ffmpeg)");

  render::StereoFrameOptions frameOptions;
  // The camera cuts choose each frame's camera unless one is named.
  const bool followCuts = !args.has("camera") && !state->sequence.cuts.empty();
  frameOptions.camera = followCuts ? scene::kNoEntity : camera;
  if (followCuts) {
    if (const std::string p = scene::cutsProblem(*state); !p.empty())
      return args.fail(scenePath + ": the camera cuts cannot be rendered: " + p);
    std::printf("following %zu camera cut(s) (frames outside them: '%s')\n", state->sequence.cuts.size(),
                cam.name.c_str());
  }
  frameOptions.showGrid = !args.flag("no_grid");
  frameOptions.displayBits16 = s.image.png16;
  if (args.flag("comfort")) {
    sequencer::ComfortOptions co;
    co.budget = budget;
    frameOptions.comfort = co;
  }
  s.jobTag = render::exportJobTag(*state, frameOptions.camera, s, frameOptions);
  if (!film && (frameOptions.comfort || !s.resume)) {
    // Frames kept by resume are not rendered again, so the comfort check
    // would not see them: a comfort run renders every frame.
    if (frameOptions.comfort && s.resume)
      std::printf("note: --comfort renders every frame (nothing is kept from an earlier run)\n");
    s.resume = false;
  }
  if (!cam.camera || cam.camera->stereo == scene::Camera::Stereo::Mono) {
    if (sequencer::layoutRendersBothEyes(s.layout))
      std::printf("note: camera '%s' is mono (no stereo rig): both eyes show its view; set its Stereo "
                  "field (camera.stereo) for a stereo pair\n", cam.name.c_str());
  }

  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) return args.fail("cannot start headless OpenGL: " + error);
  render::StereoFrameSource source(renderer, *state, frameOptions);
  if (frameOptions.comfort)
    source.onComfort = [](const sequencer::FrameComfort& fc) {
      const sequencer::ComfortResult& r = fc.result;
      std::printf("frame %lld: nearest %s at %s, farthest %s at %s%s%s\n", static_cast<long long>(fc.frame),
                  percent(r.nearestParallax).c_str(), metres(r.nearestDepth).c_str(),
                  percent(r.farthestParallax).c_str(), metres(r.farthestDepth).c_str(),
                  r.withinBudget ? "" : "  OUTSIDE BUDGET: ", r.withinBudget ? "" : r.message.c_str());
    };

  ProgressPrinter printer;
  sequencer::ExportCallbacks callbacks;
  callbacks.onFrame = [&printer](const sequencer::ExportProgress& p) { printer(p); };
  callbacks.progress = &gInterrupted;
  std::signal(SIGINT, onInterrupt);
  const sequencer::ExportResult r = sequencer::runExport(s, source, callbacks);
  std::signal(SIGINT, SIG_DFL);
  printer.end();

  // Notes and warnings go to stdout: stderr carries progress and, on
  // failure, exactly one line with the reason.
  for (const std::string& w : source.warnings()) std::printf("warning: %s\n", w.c_str());
  for (const std::string& p : render::takeRenderProblems(renderer.renderer())) std::printf("warning: %s\n", p.c_str());
  for (const std::string& n : r.notes) std::printf("%s\n", n.c_str());
  if (frameOptions.comfort) {
    const std::vector<int64_t> bad = sequencer::framesOutsideBudget(source.comfort());
    std::printf("comfort: %zu of %zu frame(s) outside the budget %s .. %s%s%s\n", bad.size(), source.comfort().size(),
                percent(budget.nearest).c_str(), percent(budget.farthest).c_str(), bad.empty() ? "" : ": ",
                bad.empty() ? "" : sequencer::FrameList::fromFrames(bad).toString().c_str());
  }
  if (!r.ok && !r.cancelled) return args.fail(r.error);
  const double fps = r.seconds > 0.0 ? double(r.rendered) / r.seconds : 0.0;
  std::printf("%s %lld frame(s), kept %lld, of %lld (%s %dx%d per eye, camera '%s') in %.2f s, %.2f fps "
              "(rendering %.2f s, encoding %.2f s on %d writer(s)) -> %s\n",
              r.cancelled ? "interrupted after" : "rendered", static_cast<long long>(r.written),
              static_cast<long long>(r.kept), static_cast<long long>(r.total), sequencer::layoutName(s.layout),
              s.eyeWidth, s.eyeHeight, cam.name.c_str(), r.seconds, fps, r.renderSeconds, r.writeSeconds,
              s.writerThreads, s.output.c_str());
  if (r.cancelled) {
    std::fprintf(stderr, "hybridscape-cli render: interrupted; run the same command again to resume\n");
    return 130;
  }
  return 0;
}

}  // namespace hs::cli
