// bench_oit (issue 13): the transparency modes side by side on one machine,
// the thesis's comparison extended. Scenes, each drawn translucent (opacity
// 0.35, two-sided, lit by a sun) over the gradient sky:
//   bunny    the Stanford Bunny (69k triangles, resources/demo)
//   stack    three bunnies one behind the other (~208k triangles, high depth complexity)
//   terrain  a 93,312-triangle terrain mesh (217 x 217 grid, as bench_frame's)
// Modes: abuffer, abuffer_fixed (16), kbuffer K = 2, 5, 10, 16, weighted;
// each against reference (depth peeling): median frame time (renderOnly,
// waits for the GPU), OIT GPU memory (--stats' oit.bytes), fragments per
// pixel (max, mean over covered pixels), and RMSE, PSNR and maximum error of
// the 8-bit image against the reference's. Prints a markdown table with the
// machine's load average, and draws PSNR against frame time
// (bench_oit.png). The thesis's GTX 760 figures are printed beside.
//
//   bench_oit [--sizes 640x480,1920x1080] [--runs 5] [--plot bench_oit.png] [--scenes bunny,stack,terrain]
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/height_grid.h"
#include "mesh/mesh_import.h"
#include "bench/common/plot.h"
#include "render/offscreen_renderer.h"
#include "render/render_view.h"
#include "scene/light_units.h"
#include "scene/mesh_materials.h"
#include "scene/transform.h"
#include "scene/world_bounds.h"
#include "sequencer/camera_path.h"

using namespace hs;

namespace {

struct Mode {
  std::string name;
  scene::Transparency t;
  int k = 8;
};

const std::vector<Mode> kModes = {
    {"abuffer", scene::Transparency::ABuffer},          {"abuffer_fixed 16", scene::Transparency::ABufferFixed},
    {"kbuffer K=2", scene::Transparency::KBuffer, 2},   {"kbuffer K=5", scene::Transparency::KBuffer, 5},
    {"kbuffer K=10", scene::Transparency::KBuffer, 10}, {"kbuffer K=16", scene::Transparency::KBuffer, 16},
    {"weighted", scene::Transparency::Weighted},
};

std::shared_ptr<const mesh::MeshData> gridTerrain() {
  return bench::heightGridMesh(217, 400.0f, [](float x, float y) {
    return 6.0f * std::sin(x * 0.03f) * std::cos(y * 0.025f) + 0.0001f * (x * x + y * y);
  });
}

// `mesh` shown `copies` times along +Y (spacing `step`), all translucent; a sun.
scene::SceneState sceneOf(std::shared_ptr<const mesh::MeshData> mesh, int copies, glm::dvec3 step, double scale) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  scene::MeshAsset a;
  a.id = 1;
  a.name = "mesh";
  a.data = std::move(mesh);
  a.contentHash = mesh::contentHash(*a.data);
  s.assets.emplace(a.id, a);
  scene::addMeshMaterials(s, a.id);
  for (auto& [id, m] : s.materials) {
    m.opacity = 0.35f;
    m.twoSided = true;
    m.baseColor = glm::vec3(0.8f, 0.7f, 0.6f);
  }
  for (int i = 0; i < copies; ++i) {
    scene::Entity e;
    e.id = scene::EntityId(10 + i);
    e.name = "copy " + std::to_string(i);
    e.mesh = scene::MeshInstance{a.id};
    e.transform.translation = step * double(i);
    e.transform.scale = glm::dvec3(scale);
    s.entities.emplace(e.id, e);
    s.roots.push_back(e.id);
  }
  scene::Entity sun;
  sun.id = 1;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({40, 0, -35});
  s.entities.emplace(sun.id, sun);
  s.roots.push_back(sun.id);
  return s;
}

struct Error {
  double rmse = 0.0, psnr = 0.0, maxError = 0.0;
};

Error compare(const Image& a, const Image& b) {
  double sum = 0.0, worst = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(a.rgba8[i]) - double(b.rgba8[i]);
    sum += d * d;
    worst = std::max(worst, std::abs(d));
    ++n;
  }
  Error e;
  e.rmse = std::sqrt(sum / double(std::max<size_t>(n, 1)));
  e.psnr = e.rmse > 0.0 ? 20.0 * std::log10(255.0 / e.rmse) : 99.0;
  e.maxError = worst;
  return e;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, ',');) out.push_back(part);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes = {"640x480"};
  std::vector<std::string> scenes = {"bunny", "stack", "terrain"};
  int runs = 5;
  std::string plotPath = "bench_oit.png";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--sizes") sizes = split(v);
    else if (a == "--runs") runs = std::max(1, std::atoi(v.c_str()));
    else if (a == "--plot") plotPath = v;
    else if (a == "--scenes") scenes = split(v);
    else {
      std::fprintf(stderr, "bench_oit: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  mesh::ImportResult bunny = mesh::importMesh(HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj");
  if (!bunny.ok()) {
    std::fprintf(stderr, "bench_oit: %s\n", bunny.error.c_str());
    return 1;
  }
  auto bunnyMesh = std::make_shared<const mesh::MeshData>(std::move(*bunny.mesh));
  std::map<std::string, scene::SceneState> states;
  states["bunny"] = sceneOf(bunnyMesh, 1, {}, 10.0);
  states["stack"] = sceneOf(bunnyMesh, 3, {0.0, 0.35, 0.0}, 10.0);
  states["terrain"] = sceneOf(gridTerrain(), 1, {}, 1.0);

  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_oit: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_oit on %s; load average before: %s\n\n", r.glDescription().c_str(), bench::loadAverageLine().c_str());
  std::printf("| scene | size | mode | median ms | CPU s/frame | OIT MB | frags/px max | mean | RMSE | PSNR dB | max err | load |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<bench::PlotPanel> panels;
  for (const std::string& size : sizes) {
    int w = 640, h = 480;
    std::sscanf(size.c_str(), "%dx%d", &w, &h);
    bench::PlotPanel panel;
    panel.title = "Error against depth peeling, " + size;
    panel.xLabel = "median frame time (ms)";
    panel.yLabel = "PSNR (dB, higher is better)";
    panel.logX = true;
    std::map<std::string, bench::PlotSeries> series;
    const bench::PlotColour colours[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44}};
    int sceneIndex = 0;
    for (const std::string& name : scenes) {
      auto found = states.find(name);
      if (found == states.end()) continue;
      scene::SceneState s = found->second;
      const scene::WorldBox box = scene::worldBounds(s);
      render::RenderView view = render::frameBox(box.min, box.max, w, h);
      // Looking along the stack's axis (+Y) so its copies lie behind each other.
      if (name == "stack") {
        view = render::frameBox(box.min, box.max, w, h);
        const glm::dvec3 c = 0.5 * (box.min + box.max);
        view.eye = c - glm::dvec3(0.0, 2.2 * glm::length(box.max - box.min), 0.15 * glm::length(box.max - box.min));
        view.orientation = sequencer::lookRotation(c - view.eye);
      }
      s.settings.transparency = scene::Transparency::Reference;
      const Image reference = r.render(s, view);
      bench::PlotSeries line;
      line.name = name;
      line.colour = colours[sceneIndex++ % 3];
      for (const Mode& m : kModes) {
        s.settings.transparency = m.t;
        s.settings.kbufferK = m.k;
        s.settings.oitMemoryMb = 1024.0;
        render::FrameStats stats;
        render::RenderOptions counted;
        counted.oitCounts = true;
        const Image img = r.render(s, view, false, &stats, counted);
        const Error e = compare(img, reference);
        r.renderOnly(s, view);  // warm
        std::vector<double> ms;
        const double cpu0 = bench::cpuSeconds(RUSAGE_SELF);
        for (int i = 0; i < runs; ++i) {
          const double t0 = bench::nowSeconds();
          r.renderOnly(s, view);
          ms.push_back((bench::nowSeconds() - t0) * 1e3);
        }
        const double cpu = (bench::cpuSeconds(RUSAGE_SELF) - cpu0) / runs;
        const double med = bench::median(ms);
        std::printf("| %s | %s | %s | %.1f | %.2f | %.1f | %u | %.2f | %.2f | %.1f | %.0f | %.2f |\n", name.c_str(),
                    size.c_str(), m.name.c_str(), med, cpu, double(stats.oit.bytes) / 1048576.0, stats.oit.maxPerPixel,
                    stats.oit.meanPerPixel, e.rmse, e.psnr, e.maxError, bench::loadAverage());
        std::fflush(stdout);
        line.points.emplace_back(med, e.psnr);
        line.pointLabels.push_back(m.name);
      }
      panel.series.push_back(line);
    }
    panels.push_back(panel);
  }
  std::printf("\nThe thesis (GTX 760, OpenGL; Stanford Dragon / Bunny / 94k terrain): A-buffer 232 / 538 / 598 fps, "
              "233 MB; K-buffer K=2 658 / 983 / 1200 fps, 155-158 MB (K=5 showed race artifacts).\n");
  std::printf("load average after: %s\n", bench::loadAverageLine().c_str());
  if (const std::string e = bench::savePlotPng(panels, plotPath); !e.empty()) std::fprintf(stderr, "plot: %s\n", e.c_str());
  else std::printf("plot: %s\n", plotPath.c_str());
  return 0;
}
