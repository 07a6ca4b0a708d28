// bench_shading: the survey's claim that Phong shading (lighting per pixel)
// costs 6-7x Gouraud shading (lighting per vertex), measured on this
// machine, with the image error of Gouraud (and flat) shading against
// per-pixel shading: a grid of Blinn-Phong spheres (the survey's model)
// filling a 1920x1080 view, at several tessellations (triangle sizes on
// screen) and with 1 or 9 lights (a sun, plus 8 point lights).
//
// Time: the opaque pass alone (GPU timestamps, RenderOptions::passTimings),
// median of N frames after warm-up, the three modes interleaved so a change
// in the machine's load hits them alike. Error: against the per-pixel image
// of the same mesh, in 8-bit sRGB: mean absolute difference over the
// spheres' pixels and the share of pixels off by more than 6 levels.
//
//   bench_shading [--frames N] [--warmup W] [--size WxH] [--plot FILE.png]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/plot.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "scene/light_units.h"
#include "scene/mesh_materials.h"

using namespace hs;
using bench::median;

namespace {

constexpr int kColumns = 6, kRows = 3;

// kColumns x kRows spheres of radius 1 in the XZ plane, seen from -Y; one
// Blinn-Phong material whose shading mode the caller sets.
scene::SceneState sphereGrid(int segments, int pointLights) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.2f;
  mesh::MeshData sphere = mesh::uvSphere(1.0f, segments, segments / 2);
  scene::MeshAsset a;
  a.id = 1;
  a.name = "Sphere";
  a.contentHash = mesh::contentHash(sphere);
  a.data = std::make_shared<const mesh::MeshData>(std::move(sphere));
  scene::Material m;
  m.id = 1;
  m.name = "Sphere / survey";
  m.asset = 1;
  m.baseColor = {0.6f, 0.35f, 0.2f};
  m.model = scene::LightingModel::BlinnPhong;
  m.specular = 0.6f;
  m.shininess = 30.0f;
  a.materialSlots.assign(scene::materialSlotCount(*a.data), m.id);
  s.materials.emplace(m.id, m);
  s.assets.emplace(a.id, a);
  scene::EntityId next = 1;
  auto add = [&](scene::Entity e) {
    e.id = next++;
    s.roots.push_back(e.id);
    s.entities.emplace(e.id, std::move(e));
  };
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      scene::Entity e;
      e.name = "Sphere";
      e.mesh = scene::MeshInstance{1};
      e.transform.translation = {(c - (kColumns - 1) * 0.5) * 2.2, 0.0, (r - (kRows - 1) * 0.5) * 2.2};
      add(e);
    }
  scene::Entity sun;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({50, 0, -30});
  add(sun);
  for (int i = 0; i < pointLights; ++i) {
    scene::Entity p;
    p.name = "Point";
    // 3.0 at 1 m in the units this bench was written in, before lights took
    // lumens (1.7 million lm): at 3 lm they no longer changed the 8-bit image.
    p.light = scene::Light{scene::Light::Type::Point, {1.0f, 0.9f, 0.8f},
                           float(scene::legacyLightIntensity(scene::Light::Type::Point, 3.0)), 30.0f};
    p.transform.translation = {(i % 4 - 1.5) * 3.5, -2.5, (i / 4 - 0.5) * 3.0};
    add(p);
  }
  return s;
}

double opaqueMs(const render::FrameStats& st) {
  for (const auto& p : st.passes)
    if (p.name == "opaque") return p.gpuMs >= 0.0 ? p.gpuMs : p.cpuMs;
  return -1.0;
}

struct ImageError {
  double meanAbs = 0.0;   // 8-bit levels, over the pixels the spheres cover
  double shareOver6 = 0.0;
};

ImageError imageError(const hs::Image& a, const hs::Image& ref) {
  ImageError e;
  size_t covered = 0, over = 0;
  double sum = 0.0;
  for (size_t i = 0; i + 3 < ref.rgba8.size(); i += 4) {
    const bool background = std::max({ref.rgba8[i], ref.rgba8[i + 1], ref.rgba8[i + 2]}) == 0 &&
                            std::max({a.rgba8[i], a.rgba8[i + 1], a.rgba8[i + 2]}) == 0;
    if (background) continue;
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(a.rgba8[i + size_t(c)]) - int(ref.rgba8[i + size_t(c)]));
      sum += d;
      worst = std::max(worst, d);
    }
    ++covered;
    if (worst > 6) ++over;
  }
  if (covered) {
    e.meanAbs = sum / double(3 * covered);
    e.shareOver6 = double(over) / double(covered);
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 9, warmup = 2, width = 1920, height = 1080;
  std::string plotPath;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--warmup" && i + 1 < argc) warmup = std::atoi(argv[++i]);
    else if (a == "--plot" && i + 1 < argc) plotPath = argv[++i];
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_shading [--frames N] [--warmup W] [--size WxH] [--plot FILE.png]\n");
      return 2;
    }
  }
  if (frames < 1 || warmup < 0 || width < 1 || height < 1) {
    std::fprintf(stderr, "bench_shading: frames and sizes must be positive\n");
    return 2;
  }
  render::OffscreenRenderer renderer;
  std::string error;
  if (!renderer.initialize(error)) {
    std::fprintf(stderr, "bench_shading: cannot start headless OpenGL: %s\n", error.c_str());
    return 1;
  }
  render::RenderView view;
  view.width = width;
  view.height = height;
  view.fovY = 2.0 * std::atan(3.6 / 14.0);
  view.eye = {0.0, -14.0, 0.0};
  view.orientation = glm::dquat(glm::dvec3(glm::radians(90.0), 0.0, 0.0));  // look along +Y, Z up
  render::RenderOptions options;
  options.passTimings = true;

  std::printf("%d x %d Blinn-Phong spheres at %dx%d, %s (EGL %s)\n"
              "opaque pass GPU time, median of %d frames after %d warm-up; load average %s on %s\n\n",
              kColumns, kRows, width, height, renderer.glDescription().c_str(), renderer.eglPlatform().c_str(),
              frames, warmup, bench::loadAverageLine().c_str(), bench::threadsText().c_str());
  std::printf("| lights | triangles (all spheres) | px per triangle | flat ms | Gouraud ms | Phong ms | Phong / Gouraud | "
              "Gouraud error: mean, >6 levels | flat error: mean, >6 levels |\n");
  std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  bench::PlotSeries ratio1{"time Phong / Gouraud, 1 light", {200, 60, 40}, bench::PlotMarker::Circle, false, {}, {}};
  bench::PlotSeries ratio9{"time Phong / Gouraud, 9 lights", {40, 90, 200}, bench::PlotMarker::Square, false, {}, {}};
  bench::PlotSeries err{"Gouraud mean error (8-bit levels)", {200, 60, 40}, bench::PlotMarker::Diamond, false, {}, {}};
  bench::PlotSeries errFlat{"flat mean error (8-bit levels)", {90, 90, 90}, bench::PlotMarker::Triangle, true, {}, {}};
  for (int lights : {0, 8})
    for (int segments : {8, 16, 32, 64, 128, 256}) {
      scene::SceneState states[3];
      const scene::ShadingMode modes[3] = {scene::ShadingMode::Flat, scene::ShadingMode::Gouraud, scene::ShadingMode::Phong};
      for (int k = 0; k < 3; ++k) {
        states[k] = sphereGrid(segments, lights);
        states[k].materials.at(1).shading = modes[k];
      }
      std::vector<double> ms[3];
      render::FrameStats st;
      for (int i = 0; i < warmup + frames; ++i)
        for (int k = 0; k < 3; ++k) {
          st = renderer.renderOnly(states[k], view, options);
          if (i >= warmup) ms[k].push_back(opaqueMs(st));
        }
      const hs::Image phong = renderer.render(states[2], view);
      const ImageError eg = imageError(renderer.render(states[1], view), phong);
      const ImageError ef = imageError(renderer.render(states[0], view), phong);
      const double t[3] = {median(ms[0]), median(ms[1]), median(ms[2])};
      const size_t tris = st.trianglesDrawn;
      // Pixels the spheres cover, from the reference image, per triangle drawn.
      size_t covered = 0;
      for (size_t i = 0; i + 3 < phong.rgba8.size(); i += 4)
        if (std::max({phong.rgba8[i], phong.rgba8[i + 1], phong.rgba8[i + 2]}) > 0) ++covered;
      // About half the triangles face away (and cover nothing).
      const double pxPerTri = double(covered) / std::max(1.0, double(tris) * 0.5);
      std::printf("| %d | %zu | %.1f | %.2f | %.2f | %.2f | %.2fx | %.2f, %.1f%% | %.2f, %.1f%% |\n", lights + 1, tris,
                  pxPerTri, t[0], t[1], t[2], t[2] / t[1], eg.meanAbs, 100.0 * eg.shareOver6, ef.meanAbs,
                  100.0 * ef.shareOver6);
      std::fflush(stdout);
      (lights ? ratio9 : ratio1).points.emplace_back(double(tris), t[2] / t[1]);
      if (!lights) {
        err.points.emplace_back(double(tris), eg.meanAbs);
        errFlat.points.emplace_back(double(tris), ef.meanAbs);
      }
    }
  if (!plotPath.empty()) {
    bench::PlotPanel time{"Phong shading's cost over Gouraud (survey: 6-7x)", "triangles drawn", "time ratio", true, false,
                          {ratio1, ratio9}};
    bench::PlotPanel accuracy{"Error against per-pixel shading, 1 light", "triangles drawn", "mean |difference|, 8-bit",
                              true, true, {err, errFlat}};
    if (const std::string e = bench::savePlotPng({time, accuracy}, plotPath); !e.empty()) {
      std::fprintf(stderr, "bench_shading: %s\n", e.c_str());
      return 1;
    }
    std::printf("\nplot: %s\n", plotPath.c_str());
  }
  return 0;
}
