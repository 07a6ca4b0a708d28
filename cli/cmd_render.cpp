#include <chrono>
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/render_frames.h"
#include "cli/sequence_options.h"
#include "render/offscreen_renderer.h"
#include "scene/hscene_file.h"
#include "scene/world_bounds.h"
#include "sequencer/image_writer.h"

namespace hs::cli {

int runRender(int argc, char** argv) {
  const char* cmd = "render";
  Args args;
  std::string error;
  std::vector<OptionSpec> specs = {{"out"}, {"size"}, {"camera"}, {"aa"}, {"no-grid", false}, {"quality"}};
  for (const OptionSpec& o : renderFramesOptionSpecs()) specs.push_back(o);
  if (!parseArgs(argc, argv, 0, specs, args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli render <scene.hscene> --out FILE [options]\n"
        "       hybridscape-cli render <scene.hscene> --frames LIST --out PATTERN [options]\n\n"
        "Renders one frame headless (EGL, no X server needed). The image type follows\n"
        "the extension: .png, .jpg, .tif (8-bit sRGB) or .exr (linear half float).\n\n"
        "  --out FILE       the image to write (required)\n"
        "  --size WxH       image size in pixels (default 1920x1080)\n"
        "  --camera NAME    camera entity to render from (default: the first camera;\n"
        "                   with no camera, a view that frames the whole scene)\n"
        "  --aa none|fxaa|msaa4   override the scene's anti-aliasing setting\n"
        "  --no-grid        hide the ground grid\n"
        "  --quality N      JPEG quality 1-100 (default 92)\n");
    std::printf("%s", renderFramesHelp());
    return 0;
  }
  // Any sequence option (--frames, --layout, --video, ...) makes it a sequence render.
  if (isSequenceRender(args)) return renderFrames(args);
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const auto out = args.get("out");
  if (!out) return usage(cmd, "--out FILE is required");
  const auto format = sequencer::imageFormatFromPath(*out);
  if (!format) return fail(cmd, *out + ": unknown image type; use .png, .exr, .jpg or .tif");
  int width = 1920, height = 1080;
  if (auto size = args.get("size"))
    if (!parseSize(*size, width, height, error)) return usage(cmd, error);
  sequencer::WriteOptions writeOptions;
  if (auto q = args.get("quality")) writeOptions.jpegQuality = std::atoi(q->c_str());

  std::optional<scene::SceneState> state = scene::loadScene(args.positional[0], error);
  if (!state) return fail(cmd, error);
  if (auto aa = args.get("aa")) {
    if (*aa == "none") state->settings.antialiasing = scene::Antialiasing::None;
    else if (*aa == "fxaa") state->settings.antialiasing = scene::Antialiasing::Fxaa;
    else if (*aa == "msaa4") state->settings.antialiasing = scene::Antialiasing::Msaa4;
    else return usage(cmd, "--aa takes none, fxaa or msaa4");
  }

  render::RenderView view;
  std::string from;
  if (auto name = args.get("camera")) {
    const scene::EntityId id = state->findByName(*name);
    if (id == scene::kNoEntity || !state->find(id)->camera) {
      std::string known;
      for (scene::EntityId c : state->cameras()) known += (known.empty() ? "" : ", ") + ("'" + state->find(c)->name + "'");
      return fail(cmd, "no camera named '" + *name + "' in " + args.positional[0] +
                           (known.empty() ? " (it has no cameras)" : " (cameras: " + known + ")"));
    }
    view = render::viewFromCamera(*state, id, width, height);
    from = "camera '" + *name + "'";
  } else if (const auto cams = state->cameras(); !cams.empty()) {
    view = render::viewFromCamera(*state, cams.front(), width, height);
    from = "camera '" + state->find(cams.front())->name + "'";
  } else {
    const scene::WorldBox box = scene::worldBounds(*state);
    view = render::frameBox(box.empty ? glm::dvec3(-5) : box.min, box.empty ? glm::dvec3(5) : box.max, width, height);
    from = "a view framing the scene";
  }

  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) return fail(cmd, "cannot start headless OpenGL: " + error);
  const auto t0 = std::chrono::steady_clock::now();
  render::FrameStats stats;
  render::RenderOptions options;
  options.showGrid = !args.has("no-grid");
  const bool hdr = *format == sequencer::ImageFormat::Exr;
  const hs::Image img = renderer.render(*state, view, hdr, &stats, options);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  hs::ImageView iv{img.width, img.height, img.rgba8.empty() ? nullptr : img.rgba8.data(),
                          img.rgbaF.empty() ? nullptr : img.rgbaF.data()};
  if (!sequencer::writeImage(*out, iv, error, writeOptions)) return fail(cmd, error);
  std::printf("rendered %dx%d from %s: %zu triangles, %zu draw calls, %.1f ms (%s) -> %s\n", width, height,
              from.c_str(), stats.trianglesDrawn, stats.drawCalls, ms, renderer.glDescription().c_str(), out->c_str());
  return 0;
}

}  // namespace hs::cli
