// bench_particles_render: frames of 100k and 1M live particles
// (render/particle_source.h) through each transparency mode, with the
// particles evaluated on the CPU (Evaluator::frame, every thread) and in
// the compute pass (settings.particles_gpu), side by side in one run. The
// emitter is a box of dust 200 x 200 m seen from above at an angle (no
// replay, so both paths take it), soft and lit; the ground is one grey
// plane. Columns: frame time (wall, GPU waited for), the CPU's part of it
// (FrameStats::cpuMs), particles drawn (the buffer's records; the GPU path
// also counts dead candidates), and the ratio of the GPU path's frame to
// the CPU path's. `reference` (depth peeling) runs only at the smallest
// count: it peels once per layer.
//
// A second table, the replay: the same dust with its preset's turbulence
// (steps of 1/30 s, lives of 4-8 s), weighted transparency, frames 1/60 s
// apart: on the CPU cold (the emitter's seed changed every frame, so its
// replay cache is empty: every particle replays from its birth, the cost
// of a farm node's first frame, frame 30,000 of the film or another), on
// the CPU warm (each frame resumes the last one's steps) and in the
// compute pass (which replays from the birth every frame: no cache).
//
//   bench_particles_render [--counts 100000,1000000] [--replay-counts 10000,100000] [--size 1920x1080] [--frames N]
#include <QCoreApplication>

#include <cstdio>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/primitives.h"
#include "particles/presets.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/scene_state.h"
#include "sequencer/camera_path.h"
#include "tests/common/scene_parts.h"

using namespace hs;

namespace {

scene::SceneState dustScene(double live, bool gpu, scene::Transparency mode, bool turbulent = false,
                            uint32_t seed = 4) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.shadows = false;
  s.settings.transparency = mode;
  s.settings.particlesOnGpu = gpu;
  s.settings.oitMemoryMb = 2048.0;
  test::addMeshAsset(s, 1, "Ground", mesh::gridPlane(400.0f, 4), {0.5f, 0.5f, 0.48f});
  test::addMeshEntity(s, 1, "Ground", 1);
  test::addSun(s, 1, {50, 0, -35});
  std::string error;
  std::vector<particles::EmitterDesc> dust =
      particles::makePreset("dust", {.area = glm::dvec4(-100, -100, 100, 100), .seed = 4}, error);
  particles::EmitterDesc d = dust.front();
  if (!turbulent) d.turbulence = 0.0;  // closed form
  d.collision = particles::CollisionMode::None;  // both paths take it
  d.seed = seed;
  d.rate = live / (0.5 * (d.lifetimeMin + d.lifetimeMax));  // steady: rate x mean lifetime
  d.maxLive = int64_t(4.0 * live);
  d.origin = glm::dvec3(0.0, 0.0, 0.3);
  scene::Entity e;
  e.id = 2;
  e.name = "Dust";
  e.particles = scene::ParticleEmitter{d};
  s.entities.emplace(e.id, e);
  s.roots.push_back(e.id);
  s.time.seconds = 30.0;
  return s;
}

// Frames 1..frames of `sceneAt(f)` (frame 0 builds programs and caches):
// the median wall time (ms), the median CPU part and the particles drawn.
struct Timing {
  double ms = 0.0, cpuMs = 0.0;
  size_t drawn = 0;
};
template <class SceneAt>
Timing timeFrames(render::OffscreenRenderer& r, const render::RenderView& v, int frames, SceneAt sceneAt) {
  std::vector<double> wall, cpu;
  Timing t;
  for (int f = 0; f < frames + 1; ++f) {
    const scene::SceneState s = sceneAt(f);
    const double t0 = bench::nowSeconds();
    const render::FrameStats st = r.renderOnly(s, v);
    if (f == 0) continue;
    wall.push_back(bench::nowSeconds() - t0);
    cpu.push_back(st.cpuMs);
    t.drawn = st.particlesDrawn;
  }
  t.ms = bench::median(wall) * 1e3;
  t.cpuMs = bench::median(cpu);
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  std::vector<double> counts = {1e5, 1e6}, replayCounts = {1e4, 1e5};
  int width = 1920, height = 1080, frames = 3;
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--counts") counts = bench::numberList(argv[++i]);
    if (a == "--replay-counts") replayCounts = bench::numberList(argv[++i]);
    if (a == "--frames") frames = std::max(1, std::atoi(argv[++i]));
    if (a == "--size" && std::sscanf(argv[i + 1], "%dx%d", &width, &height) == 2) ++i;
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_particles_render: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_particles_render: %dx%d, %s; %s; load %.2f\n", width, height, r.glDescription().c_str(),
              bench::threadsText().c_str(), bench::loadAverage());
  std::printf("%10s %-14s %-4s %10s %10s %12s %9s\n", "live", "mode", "eval", "frame ms", "CPU ms", "particles",
              "GPU/CPU");
  render::RenderView v;
  v.width = width;
  v.height = height;
  v.fovY = glm::radians(50.0);
  v.eye = {0.0, -140.0, 60.0};
  v.orientation = sequencer::lookRotation(glm::dvec3(0.0, 140.0, -60.0));
  const std::pair<scene::Transparency, const char*> modes[] = {{scene::Transparency::ABuffer, "abuffer"},
                                                               {scene::Transparency::ABufferFixed, "abuffer_fixed"},
                                                               {scene::Transparency::KBuffer, "kbuffer"},
                                                               {scene::Transparency::Weighted, "weighted"},
                                                               {scene::Transparency::Reference, "reference"}};
  for (double live : counts) {
    for (const auto& [mode, name] : modes) {
      if (mode == scene::Transparency::Reference && live > counts.front()) continue;
      double cpuPath = 0.0;
      for (bool gpu : {false, true}) {
        const scene::SceneState s = dustScene(live, gpu, mode);
        const Timing t = timeFrames(r, v, frames, [&](int) { return s; });
        if (!gpu) cpuPath = t.ms;
        std::printf("%10.0f %-14s %-4s %10.1f %10.1f %12zu %9s\n", live, name, gpu ? "GPU" : "CPU", t.ms, t.cpuMs,
                    t.drawn, gpu ? (std::to_string(t.ms / cpuPath).substr(0, 5)).c_str() : "");
        std::fflush(stdout);
      }
    }
  }

  std::printf("\nreplay (turbulence, steps of 1/30 s), weighted transparency, frames 1/60 s apart\n");
  std::printf("%10s %-10s %10s %10s %12s %9s\n", "live", "eval", "frame ms", "CPU ms", "particles", "/CPU warm");
  enum class Path { CpuCold, CpuWarm, Gpu };
  const std::pair<Path, const char*> paths[] = {{Path::CpuWarm, "CPU warm"}, {Path::CpuCold, "CPU cold"},
                                                {Path::Gpu, "GPU"}};
  for (double live : replayCounts) {
    double warm = 0.0;
    for (const auto& [path, name] : paths) {
      // Frame 0 also fills the warm path's cache.
      const Timing t = timeFrames(r, v, frames, [&, path = path](int f) {
        scene::SceneState s = dustScene(live, path == Path::Gpu, scene::Transparency::Weighted, true,
                                        path == Path::CpuCold ? uint32_t(100 + f) : 4u);
        s.time.seconds = 30.0 + f / 60.0;
        return s;
      });
      if (path == Path::CpuWarm) warm = t.ms;
      std::printf("%10.0f %-10s %10.1f %10.1f %12zu %9.2f\n", live, name, t.ms, t.cpuMs, t.drawn, t.ms / warm);
      std::fflush(stdout);
    }
  }
  return 0;
}
