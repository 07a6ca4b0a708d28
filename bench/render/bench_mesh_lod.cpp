// bench_mesh_lod: what the mesh LOD pixel bound (SceneSettings::
// meshLodErrorPixels, render/mesh_lod.h) buys and what it costs. A field of
// instances of the demo's bunny (three LOD levels) seen from one side at
// 1920x1080: for each bound, triangles drawn, instances at a coarser level,
// GPU frame time (renderOnly, glFinish), and the image's difference from the
// full-resolution image (bound 0): largest channel difference and the share
// of pixels differing by more than 16/255. The approximation's error against
// its run time, side by side with drawing everything at full resolution.
//
//   bench_mesh_lod [--frames N] [--size WxH] [--grid N] [--spacing M]
#include <QCoreApplication>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "bench/common/bench_util.h"
#include "render/offscreen_renderer.h"
#include "scene/demo_scene.h"
#include "sequencer/camera_path.h"
#include "tests/common/image_compare.h"

using namespace hs;
using bench::loadAverage;
using bench::median;

namespace {

test::Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

// The demo's bunny asset (with its LOD chain) on a grid x grid field,
// `spacing` metres apart, each 2 m tall and turned its own way, plus a sun
// and a camera at eye height looking along the field's diagonal.
scene::SceneState field(const scene::SceneState& demo, int grid, double spacing) {
  scene::SceneState s;
  s.settings = demo.settings;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::Msaa4;
  const scene::MeshAsset* asset = nullptr;
  for (const auto& [id, a] : demo.assets)
    if (!a.lods.empty()) asset = &a;
  if (!asset) return s;
  s.assets.emplace(asset->id, *asset);
  auto add = [&](scene::Entity e) {
    e.id = s.maxEntityId() + 1;
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, e);
    return e.id;
  };
  const mesh::Bounds b = asset->data->bounds();
  const double scale = 2.0 / double(b.max.z - b.min.z);
  const glm::dvec3 base(b.center().x, b.center().y, b.min.z);
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      scene::Entity e;
      e.name = "Bunny " + std::to_string(i) + "," + std::to_string(j);
      e.mesh = scene::MeshInstance{asset->id};
      const glm::dquat r = glm::angleAxis(double((i * 7 + j * 13) % 36) * 10.0 * M_PI / 180.0, glm::dvec3(0, 0, 1));
      e.transform.rotation = r;
      e.transform.scale = glm::dvec3(scale);
      e.transform.translation = glm::dvec3(i * spacing, j * spacing, 0.0) - r * (base * scale);
      add(e);
    }
  for (const auto& [id, e] : demo.entities)
    if (e.light) add(e);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 40.0;
  // At one corner, 1.7 m up, looking along the diagonal 4 degrees down.
  const glm::dvec3 eye(-4.0, -4.0, 1.7);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 1.0, -0.07));
  cam.transform.translation = eye;
  cam.transform.rotation = sequencer::lookRotation(dir);
  add(cam);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  int frames = 5, width = 1920, height = 1080, grid = 12;
  double spacing = 6.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--grid" && i + 1 < argc) grid = std::atoi(argv[++i]);
    else if (a == "--spacing" && i + 1 < argc) spacing = std::atof(argv[++i]);
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_mesh_lod [--frames N] [--size WxH] [--grid N] [--spacing M]\n");
      return 2;
    }
  }
  if (frames < 1 || width < 1 || height < 1 || grid < 1 || !(spacing > 0)) {
    std::fprintf(stderr, "bench_mesh_lod: frames, sizes, grid and spacing must be positive\n");
    return 2;
  }
  std::string error;
  const std::optional<scene::SceneState> demo = scene::buildDemoScene(error);
  if (!demo) {
    std::fprintf(stderr, "bench_mesh_lod: %s\n", error.c_str());
    return 1;
  }
  scene::SceneState s = field(*demo, grid, spacing);
  if (s.assets.empty()) {
    std::fprintf(stderr, "bench_mesh_lod: the demo's bunny has no LOD levels\n");
    return 1;
  }
  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) {
    std::fprintf(stderr, "bench_mesh_lod: cannot start headless OpenGL: %s\n", error.c_str());
    return 1;
  }
  const scene::MeshAsset& asset = s.assets.begin()->second;
  std::printf("# Mesh LODs: %d x %d bunnies %.1f m apart, 2 m tall, at %dx%d, MSAA 4x; %s (EGL %s)\n", grid, grid,
              spacing, width, height, renderer.glDescription().c_str(), renderer.eglPlatform().c_str());
  std::printf("levels: %zu", asset.data->triangleCount());
  for (const auto& l : asset.lods) std::printf(", %zu (%.3g m)", l.triangles, l.hausdorff);
  std::printf(" triangles (Hausdorff from level 0, bunny units)\n");
  std::printf("median of %d frames each, the bounds interleaved; load average %.2f on %s\n\n", frames,
              loadAverage(), hs::bench::threadsText().c_str());

  const render::RenderView view = render::viewFromCamera(s, s.cameras().front(), width, height);
  const std::vector<double> bounds = {0.0, 0.5, 1.0, 2.0, 4.0, 8.0};
  std::vector<std::vector<double>> times(bounds.size());
  std::vector<render::FrameStats> stats(bounds.size());
  std::vector<hs::Image> images(bounds.size());
  for (size_t k = 0; k < bounds.size(); ++k) {  // warm-up, the images, GPU caches filled
    s.settings.meshLodErrorPixels = bounds[k];
    images[k] = renderer.render(s, view, false, &stats[k]);
  }
  for (int f = 0; f < frames; ++f)
    for (size_t k = 0; k < bounds.size(); ++k) {
      s.settings.meshLodErrorPixels = bounds[k];
      const auto t0 = std::chrono::steady_clock::now();
      renderer.renderOnly(s, view);
      times[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  std::printf("| bound px | instances drawn | at a coarser level | triangles drawn | frame ms | time / full | "
              "triangles / full | max channel diff | pixels differing > 16/255 |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const double fullMs = median(times[0]);
  for (size_t k = 0; k < bounds.size(); ++k) {
    const test::CompareResult c = test::compareImages(toTest(images[k]), toTest(images[0]), 16);
    const double ms = median(times[k]);
    std::printf("| %s | %zu | %zu | %zu | %.1f | %.2fx | %.3fx | %d | %.3f%% |\n",
                k == 0 ? "0 (full)" : (std::to_string(bounds[k]).substr(0, 3)).c_str(), stats[k].instancesDrawn,
                stats[k].instancesAtCoarserLod, stats[k].trianglesDrawn, ms, ms / fullMs,
                double(stats[k].trianglesDrawn) / double(stats[0].trianglesDrawn), c.maxChannelDiff,
                100.0 * c.differingShare);
  }
  return 0;
}
