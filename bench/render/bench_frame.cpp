// bench_frame: the frame graph against the renderer before it, one frame
// and one stereo pair, at 1920x1080, on two scenes:
//   demo     scene::buildDemoScene (three bunnies, the CDLOD valley, sun)
//   mesh94k  the demo's bunnies on a 93,312-triangle terrain *mesh* (a
//            217x217 grid, the size of the thesis's terrain model), no
//            CDLOD terrain
// For each: a mono frame (OffscreenRenderer::renderOnly, waited for), a
// stereo frame (both eyes of the demo camera's rig; LODs from the mono view)
// and, where the build has a frame graph, each pass's GPU time from
// timestamps and the bytes of what it created.
//
// The same source builds against the renderer before the frame graph
// (commit 0997da7: no frame graph, a stereo frame was one render() per eye);
// `--against OLD_BINARY` runs that build's bench_frame between rounds of its
// own, so both see the same machine load, and prints ratios.
//
//   bench_frame [--frames N] [--size WxH] [--json] [--against OLD] [--rounds R]
#include <QCoreApplication>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/height_grid.h"
#include "core/json.h"
#include "render/offscreen_renderer.h"
#include "render/stereo_views.h"
#include "scene/demo_scene.h"

#if __has_include("render/frame_graph.h")
#define HS_BENCH_FRAME_GRAPH 1
#else
#define HS_BENCH_FRAME_GRAPH 0
#endif

using namespace hs;
using bench::median;

namespace {

template <class F>
double millis(F&& f) {
  const double t0 = bench::nowSeconds();
  f();
  return 1000.0 * (bench::nowSeconds() - t0);
}

struct Options {
  int frames = 5, width = 1920, height = 1080, rounds = 3;
  bool json = false;
  std::string against;
};

// A terrain as a plain mesh: 217 x 217 vertices over 400 m, rolling hills.
std::shared_ptr<const mesh::MeshData> gridTerrain() {
  return bench::heightGridMesh(217, 400.0f, [](float x, float y) {
    const float h = 6.0f * std::sin(x * 0.03f) * std::cos(y * 0.025f) + 0.002f * (x * x + y * y) * 0.05f;
    return h - 0.5f;
  });
}

scene::SceneState meshTerrainScene(scene::SceneState s) {
  for (auto it = s.entities.begin(); it != s.entities.end();) {
    if (it->second.terrain) {
      std::erase(s.roots, it->first);
      it = s.entities.erase(it);
    } else {
      ++it;
    }
  }
  s.terrains.clear();
  scene::MeshAsset asset;
  asset.id = 1000;
  asset.name = "terrain mesh";
  asset.data = gridTerrain();
  asset.contentHash = mesh::contentHash(*asset.data);
  s.assets.emplace(asset.id, asset);
  scene::Entity e;
  e.name = "Terrain mesh";
  e.mesh = scene::MeshInstance{asset.id};
  scene::EntityId id = 1;
  while (s.entities.count(id)) ++id;
  e.id = id;
  s.entities.emplace(id, e);
  s.roots.push_back(id);
  return s;
}

struct SceneResult {
  std::string name;
  double monoMs = 0.0, stereoMs = 0.0;
  size_t triangles = 0;
  std::map<std::string, std::vector<double>> passGpu;  // per pass name, one per frame
  std::map<std::string, size_t> passBytes;
  std::vector<std::string> passOrder;  // as they ran
};

SceneResult measure(render::OffscreenRenderer& r, const std::string& name, const scene::SceneState& s,
                    const Options& o) {
  SceneResult out;
  out.name = name;
  const scene::EntityId cam = render::shotCamera(s);
  const render::EyeViews views = render::eyeViews(s, cam, o.width, o.height);
  render::RenderOptions opt;
  opt.lodView = &views.mono;
  std::vector<double> mono, stereo;
  r.renderOnly(s, views.mono, opt);  // warm-up: uploads, programs
  for (int f = 0; f < o.frames; ++f) {
    // Interleaved, so a change in load affects both alike.
    mono.push_back(millis([&] { out.triangles = r.renderOnly(s, views.mono, opt).trianglesDrawn; }));
    stereo.push_back(millis([&] {
#if HS_BENCH_FRAME_GRAPH
      r.renderViewsOnly(s, {views.left, views.right}, opt);
#else
      r.renderOnly(s, views.left, opt);
      r.renderOnly(s, views.right, opt);
#endif
    }));
  }
  out.monoMs = median(mono);
  out.stereoMs = median(stereo);
#if HS_BENCH_FRAME_GRAPH
  render::RenderOptions timed = opt;
  timed.passTimings = true;
  auto record = [&out](const render::FrameStats& st) {
    for (const render::PassStats& p : st.passes) {
      if (!out.passGpu.count(p.name)) out.passOrder.push_back(p.name);
      out.passGpu[p.name].push_back(p.gpuMs);
      out.passBytes[p.name] = p.gpuBytes;
    }
  };
  for (int f = 0; f < o.frames; ++f) {
    record(r.renderOnly(s, views.mono, timed));
    record(r.renderViewsOnly(s, {views.left, views.right}, timed));  // passes named "...[left]", "...[right]"
  }
#endif
  return out;
}

Json toJson(const std::vector<SceneResult>& results) {
  Json j;
  j["frame_graph"] = bool(HS_BENCH_FRAME_GRAPH);
  j["scenes"] = Json::array();
  for (const SceneResult& r : results)
    j["scenes"].push_back({{"name", r.name}, {"mono_ms", r.monoMs}, {"stereo_ms", r.stereoMs}, {"triangles", r.triangles}});
  return j;
}

std::optional<Json> runOld(const Options& o, std::string& error) {
  const std::string cmd = o.against + " --json --frames " + std::to_string(o.frames) + " --size " +
                          std::to_string(o.width) + "x" + std::to_string(o.height);
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    error = "cannot run " + o.against;
    return std::nullopt;
  }
  std::string text;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, p)) text.append(buf, n);
  if (pclose(p) != 0) {
    error = o.against + " failed";
    return std::nullopt;
  }
  return parseJson(text, error);
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) o.frames = std::atoi(argv[++i]);
    else if (a == "--rounds" && i + 1 < argc) o.rounds = std::atoi(argv[++i]);
    else if (a == "--against" && i + 1 < argc) o.against = argv[++i];
    else if (a == "--json") o.json = true;
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_frame [--frames N] [--size WxH] [--json] [--against OLD] [--rounds R]\n");
      return 2;
    }
  }
  if (o.frames < 1 || o.rounds < 1 || o.width < 1 || o.height < 1) {
    std::fprintf(stderr, "bench_frame: frames, rounds and sizes must be positive\n");
    return 2;
  }
  std::string error;
  std::optional<scene::SceneState> demo = scene::buildDemoScene(error);
  if (!demo) {
    std::fprintf(stderr, "bench_frame: %s\n", error.c_str());
    return 1;
  }
  const scene::SceneState meshScene = meshTerrainScene(*demo);
  render::OffscreenRenderer r;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_frame: %s\n", error.c_str());
    return 1;
  }
  auto measureAll = [&] {
    return std::vector<SceneResult>{measure(r, "demo", *demo, o), measure(r, "mesh94k", meshScene, o)};
  };
  if (o.json) {
    std::printf("%s\n", writeJson(toJson(measureAll()), -1).c_str());
    return 0;
  }

  std::printf("# bench_frame at %dx%d, %s (EGL %s)\n", o.width, o.height, r.glDescription().c_str(),
              r.eglPlatform().c_str());
  std::printf("median of %d frames per round, median of %d rounds%s; load (/proc/loadavg) %s\n\n", o.frames,
              o.rounds, o.against.empty() ? "" : (", each round also running " + o.against).c_str(),
              bench::loadAverageLine().c_str());
  std::map<std::string, std::vector<double>> oldMono, oldStereo, newMono, newStereo;
  std::vector<SceneResult> last;
  for (int round = 0; round < o.rounds; ++round) {
    if (!o.against.empty()) {
      std::optional<Json> old = runOld(o, error);
      if (!old) {
        std::fprintf(stderr, "bench_frame: %s\n", error.c_str());
        return 1;
      }
      for (const Json& s : (*old)["scenes"]) {
        oldMono[s["name"].get<std::string>()].push_back(s["mono_ms"].get<double>());
        oldStereo[s["name"].get<std::string>()].push_back(s["stereo_ms"].get<double>());
      }
    }
    last = measureAll();
    for (const SceneResult& s : last) {
      newMono[s.name].push_back(s.monoMs);
      newStereo[s.name].push_back(s.stereoMs);
    }
  }

  std::printf("| scene | triangles | mono ms | stereo ms | stereo / mono |%s\n",
              o.against.empty() ? "" : " before: mono ms | stereo ms | stereo / mono | mono after / before |");
  std::printf("| --- | ---: | ---: | ---: | ---: |%s\n", o.against.empty() ? "" : " ---: | ---: | ---: | ---: |");
  for (const SceneResult& s : last) {
    const double m = median(newMono[s.name]), st = median(newStereo[s.name]);
    std::printf("| %s | %zu | %.1f | %.1f | %.2fx |", s.name.c_str(), s.triangles, m, st, st / m);
    if (!o.against.empty()) {
      const double om = median(oldMono[s.name]), os = median(oldStereo[s.name]);
      std::printf(" %.1f | %.1f | %.2fx | %.2fx |", om, os, os / om, m / om);
    }
    std::printf("\n");
  }
#if HS_BENCH_FRAME_GRAPH
  for (const SceneResult& s : last) {
    std::printf("\n%s, a mono frame and a stereo frame by pass (GPU timestamps, each pass fenced, median of %d; "
                "memory the pass created):\n\n",
                s.name.c_str(), o.frames);
    std::printf("| pass | GPU ms | share of its frame | created MB |\n| --- | ---: | ---: | ---: |\n");
    // Stereo passes are named "...[left]" / "...[right]"; the rest, mono.
    auto stereoPass = [](const std::string& n) { return n.find('[') != std::string::npos; };
    double monoTotal = 0.0, stereoTotal = 0.0;
    for (const auto& [name, ms] : s.passGpu) (stereoPass(name) ? stereoTotal : monoTotal) += median(ms);
    for (int stereo = 0; stereo < 2; ++stereo) {
      for (const std::string& name : s.passOrder) {
        if (stereoPass(name) != bool(stereo)) continue;
        const double ms = median(s.passGpu.at(name));
        std::printf("| %s | %.2f | %.0f%% | %.1f |\n", name.c_str(), ms, 100.0 * ms / (stereo ? stereoTotal : monoTotal),
                    double(s.passBytes.at(name)) / (1024.0 * 1024.0));
      }
      std::printf("| **%s frame** | %.2f | | |\n", stereo ? "stereo" : "mono", stereo ? stereoTotal : monoTotal);
    }
  }
#endif
  return 0;
}
