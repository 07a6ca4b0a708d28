// bench_render: headless frame time of the demo scene (scene::buildDemoScene)
// at 1920x1080 from its camera, for each anti-aliasing mode, through
// OffscreenRenderer::renderOnly (GPU work, waited for with glFinish) and
// render() (the same plus reading the image back, as the CLI and the export
// loop do). Median of N frames after warm-up frames.
//
//   bench_render [--frames N] [--warmup W] [--size WxH]
#include <QCoreApplication>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/common/bench_util.h"
#include "render/offscreen_renderer.h"
#include "scene/demo_scene.h"

using namespace hs;
using bench::median;

namespace {

template <class F>
double millis(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  int frames = 15, warmup = 3, width = 1920, height = 1080;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--warmup" && i + 1 < argc) warmup = std::atoi(argv[++i]);
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_render [--frames N] [--warmup W] [--size WxH]\n");
      return 2;
    }
  }
  if (frames < 1 || warmup < 0 || width < 1 || height < 1) {
    std::fprintf(stderr, "bench_render: frames, sizes must be positive\n");
    return 2;
  }

  std::string error;
  std::optional<scene::SceneState> demo = scene::buildDemoScene(error);
  if (!demo) {
    std::fprintf(stderr, "bench_render: %s\n", error.c_str());
    return 1;
  }
  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) {
    std::fprintf(stderr, "bench_render: cannot start headless OpenGL: %s\n", error.c_str());
    return 1;
  }
  const auto cams = demo->cameras();
  const render::RenderView view = render::viewFromCamera(*demo, cams.front(), width, height);

  struct Mode {
    const char* name;
    scene::Antialiasing aa;
  };
  std::printf("demo scene at %dx%d from '%s', %s (EGL %s)\nmedian of %d frames after %d warm-up frames; load average %.2f on %s\n\n",
              width, height, demo->find(cams.front())->name.c_str(), renderer.glDescription().c_str(),
              renderer.eglPlatform().c_str(), frames, warmup, bench::loadAverage(), bench::threadsText().c_str());
  std::printf("| anti-aliasing | renderOnly ms | render + readback ms | difference ms | frames/s (with readback) | triangles drawn | draw calls |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const Mode& m : {Mode{"none", scene::Antialiasing::None}, Mode{"FXAA", scene::Antialiasing::Fxaa},
                        Mode{"MSAA 4x", scene::Antialiasing::Msaa4}}) {
    scene::SceneState state = *demo;
    state.settings.antialiasing = m.aa;
    render::FrameStats stats;
    for (int i = 0; i < warmup; ++i) {
      renderer.renderOnly(state, view);
      renderer.render(state, view);
    }
    // Interleaved, so a change in machine load hits both columns alike.
    std::vector<double> only, full;
    size_t pixels = 0;
    for (int i = 0; i < frames; ++i) {
      only.push_back(millis([&] { stats = renderer.renderOnly(state, view); }));
      full.push_back(millis([&] { pixels = renderer.render(state, view).rgba8.size() / 4; }));
    }
    if (pixels != size_t(width) * size_t(height)) {
      std::fprintf(stderr, "bench_render: read back %zu pixels, expected %d\n", pixels, width * height);
      return 1;
    }
    const double o = median(only), f = median(full);
    std::printf("| %s | %.1f | %.1f | %+.1f | %.1f | %zu | %zu |\n", m.name, o, f, f - o, 1000.0 / f,
                stats.trianglesDrawn, stats.drawCalls);
  }
  return 0;
}
