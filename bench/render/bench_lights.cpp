// bench_lights: the clustered light list against every pixel looping over
// every light (docs/rendering.md, "Lights and exposure").
//
// A 400 x 400 m Lambert test floor seen from 12 m up, looking over it, and
// N point and spot lights (every third a spot) scattered over the part of
// the floor in view, 0.5 to 3 m up, ranges 6 to 20 m; N = 1, 4, 16, 64,
// 256. For each N and size: the frame time (median of --frames, the GPU
// waited for) clustered and brute force (RenderOptions::bruteForceLights),
// their ratio, the light_culling and opaque passes' GPU time (fenced
// timestamps), and the largest difference between the two HDR images
// relative to the brighter. Then, with 64 lights, a stereo pair: the
// culling pass bins a grid per eye (one pass, one dispatch per eye).
//
//   bench_lights [--frames N] [--plot FILE.png] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/plot.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "scene/mesh_materials.h"
#include "tests/common/look_from.h"

using namespace hs;
using bench::median;

namespace {

struct Options {
  int frames = 5;
  std::string plot;
  bool quick = false;
};

scene::SceneState floorWithLights(int count) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.05f;
  scene::MeshAsset a;
  a.id = 1;
  a.name = "floor";
  auto plane = std::make_shared<mesh::MeshData>(mesh::gridPlane(400.0f, 64));
  a.contentHash = mesh::contentHash(*plane);
  a.data = plane;
  scene::Material m;
  m.id = 1;
  m.asset = 1;
  m.name = "floor";
  m.baseColor = glm::vec3(0.7f);
  m.model = scene::LightingModel::Lambert;
  a.materialSlots.assign(scene::materialSlotCount(*a.data), m.id);
  s.materials.emplace(m.id, m);
  s.assets.emplace(a.id, a);
  scene::Entity e;
  e.id = 1;
  e.name = "floor";
  e.mesh = scene::MeshInstance{a.id};
  s.roots.push_back(e.id);
  s.entities.emplace(e.id, e);
  std::mt19937 rng(7);
  // In front of the camera (at y = -40, looking along +y and down).
  std::uniform_real_distribution<double> x(-60.0, 60.0), y(-30.0, 90.0), z(0.5, 3.0), range(6.0, 20.0),
      tilt(-50.0, 50.0);
  for (int i = 0; i < count; ++i) {
    scene::Entity l;
    l.id = scene::EntityId(100 + i);
    l.name = "lamp";
    scene::Light light;
    light.type = i % 3 == 2 ? scene::Light::Type::Spot : scene::Light::Type::Point;
    light.intensity = 8e5f;
    light.range = float(range(rng));
    light.color = {float(0.4 + 0.6 * (i % 5) / 4.0), float(0.4 + 0.6 * (i % 7) / 6.0), 1.0f};
    light.innerConeDeg = 40.0f;
    light.outerConeDeg = 80.0f;
    l.light = light;
    l.transform.translation = {x(rng), y(rng), z(rng)};
    l.transform.rotation = scene::fromEulerDegrees({tilt(rng), tilt(rng), 0.0});
    s.roots.push_back(l.id);
    s.entities.emplace(l.id, l);
  }
  return s;
}

render::RenderView viewOf(int w, int h) {
  render::RenderView v;
  v.width = w;
  v.height = h;
  v.fovY = glm::radians(50.0);
  v.eye = {0.0, -40.0, 12.0};
  v.orientation = test::lookFrom(v.eye, {0.0, 30.0, 0.0}).rotation;
  return v;
}

double passMs(const render::FrameStats& st, const std::string& name) {
  double ms = 0.0;
  for (const render::PassStats& p : st.passes)
    if (p.name.rfind(name, 0) == 0 && p.gpuMs > 0.0) ms += p.gpuMs;
  return ms;
}

struct Row {
  int lights = 0, width = 0, height = 0;
  size_t inView = 0;
  double clusteredMs = 0, bruteMs = 0, cullMs = 0, opaqueClusteredMs = 0, opaqueBruteMs = 0, worstDiff = 0;
};

Row measure(render::OffscreenRenderer& r, int count, int w, int h, const Options& o) {
  const scene::SceneState s = floorWithLights(count);
  const render::RenderView view = viewOf(w, h);
  render::RenderOptions clustered, brute;
  brute.bruteForceLights = true;
  Row row{count, w, h};
  // Accuracy: the two HDR images.
  render::FrameStats st;
  const hs::Image a = r.render(s, view, true, &st, clustered);
  const hs::Image b = r.render(s, view, true, nullptr, brute);
  row.inView = st.lightsInView;
  for (size_t i = 0; i < a.rgbaF.size(); ++i)
    if (i % 4 != 3)
      row.worstDiff = std::max(row.worstDiff, double(std::abs(a.rgbaF[i] - b.rgbaF[i])) /
                                                  std::max({1e-6, double(std::abs(a.rgbaF[i])), double(std::abs(b.rgbaF[i]))}));
  // Frame time, alternating so load changes hit both alike.
  std::vector<double> tc, tb, cull, oc, ob;
  render::RenderOptions timedC = clustered, timedB = brute;
  timedC.passTimings = timedB.passTimings = true;
  for (int f = 0; f < o.frames; ++f) {
    double t0 = bench::nowSeconds();
    r.renderOnly(s, view, clustered);
    tc.push_back((bench::nowSeconds() - t0) * 1e3);
    t0 = bench::nowSeconds();
    r.renderOnly(s, view, brute);
    tb.push_back((bench::nowSeconds() - t0) * 1e3);
  }
  for (int f = 0; f < std::max(1, o.frames / 2); ++f) {
    const render::FrameStats c = r.renderOnly(s, view, timedC);
    cull.push_back(passMs(c, "light_culling"));
    oc.push_back(passMs(c, "opaque"));
    ob.push_back(passMs(r.renderOnly(s, view, timedB), "opaque"));
  }
  row.clusteredMs = median(tc);
  row.bruteMs = median(tb);
  row.cullMs = median(cull);
  row.opaqueClusteredMs = median(oc);
  row.opaqueBruteMs = median(ob);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) o.frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--plot" && i + 1 < argc) o.plot = argv[++i];
    else if (a == "--quick") o.quick = true;
    else {
      std::fprintf(stderr, "usage: bench_lights [--frames N] [--plot FILE.png] [--quick]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_lights: %s\n", error.c_str());
    return 1;
  }
  const double cpu0 = bench::cpuSeconds(RUSAGE_SELF);
  std::printf("bench_lights, %s; load %s\n\n", r.glDescription().c_str(), bench::loadAverageLine().c_str());
  std::printf("| size | lights (in view) | clustered ms | brute force ms | brute / clustered | light_culling GPU ms | "
              "opaque GPU ms clustered / brute | largest difference |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  const std::vector<int> counts = o.quick ? std::vector<int>{1, 16, 64} : std::vector<int>{1, 4, 16, 64, 256};
  std::vector<Row> rows;
  for (auto [w, h] : {std::pair{1920, 1080}, std::pair{640, 480}})
    for (int n : counts) {
      const Row row = measure(r, n, w, h, o);
      rows.push_back(row);
      std::printf("| %dx%d | %d (%zu) | %.1f | %.1f | %.2fx | %.2f | %.1f / %.1f | %.1e |\n", w, h, n, row.inView,
                  row.clusteredMs, row.bruteMs, row.bruteMs / row.clusteredMs, row.cullMs, row.opaqueClusteredMs,
                  row.opaqueBruteMs, row.worstDiff);
      std::fflush(stdout);
    }

  // Stereo: one culling pass bins both eyes' grids.
  {
    const scene::SceneState s = floorWithLights(64);
    render::RenderView left = viewOf(1920, 1080), right = left;
    left.eye -= 0.0325 * left.right();
    right.eye += 0.0325 * right.right();
    render::RenderOptions timed;
    timed.passTimings = true;
    std::vector<double> mono, stereo;
    for (int f = 0; f < std::max(1, o.frames / 2); ++f) {
      mono.push_back(passMs(r.renderOnly(s, viewOf(1920, 1080), timed), "light_culling"));
      stereo.push_back(passMs(r.renderViewsOnly(s, {left, right}, timed), "light_culling"));
    }
    std::printf("\nStereo, 64 lights, 1920x1080 per eye: light_culling %.2f ms for one view, %.2f ms for both eyes' "
                "grids\n",
                median(mono), median(stereo));
  }
  std::printf("CPU %.1f s (user + sys); load %s\n", bench::cpuSeconds(RUSAGE_SELF) - cpu0,
              bench::loadAverageLine().c_str());

  if (!o.plot.empty()) {
    std::vector<bench::PlotPanel> panels;
    for (auto [w, h] : {std::pair{1920, 1080}, std::pair{640, 480}}) {
      bench::PlotPanel p{"Frame time at " + std::to_string(w) + "x" + std::to_string(h), "point and spot lights",
                         "frame time (ms)", true, true, {}};
      bench::PlotSeries c{"clustered", {40, 120, 200}, bench::PlotMarker::Circle, false, {}, {}};
      bench::PlotSeries b{"brute force", {200, 60, 40}, bench::PlotMarker::Square, true, {}, {}};
      for (const Row& row : rows)
        if (row.width == w) {
          c.points.emplace_back(row.lights, row.clusteredMs);
          b.points.emplace_back(row.lights, row.bruteMs);
        }
      p.series = {c, b};
      panels.push_back(p);
    }
    const std::string err = bench::savePlotPng(panels, o.plot);
    if (!err.empty()) std::fprintf(stderr, "bench_lights: plot: %s\n", err.c_str());
    else std::printf("plot: %s\n", o.plot.c_str());
  }
  return 0;
}
