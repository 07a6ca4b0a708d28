// bench_instances: 10k, 100k and 1M instances of a 2,048-triangle sphere
// drawn three ways (render/draw_source.h, render/instanced_source.h):
//   (a) entities   one document mesh entity per instance: the mesh source,
//                  one draw call and one 144-byte object block each
//   (b) cpu        the instanced source culled on the CPU (in double),
//                  one instanced draw per type from CPU lists
//   (c) gpu        the instanced source culled by a compute pass into
//                  indirect commands (glMultiDrawElementsIndirect)
// The instances stand 2 m apart on a square field; the camera looks
// straight down from 60 m, so every count shows about the same few hundred
// instances and what grows with the count is culling and memory. No sun
// shadow: each shadow view would draw most of the field (a separate
// question, the cascades' caster count).
//
// Columns: frame time (wall, the GPU waited for), CPU time of the render
// call (FrameStats::cpuMs), draw calls, instances visible (the CPU's
// count, or the GPU's counts read back a frame later), GPU bytes per
// instance (the registry's total against the same scene without
// instances, divided by the count).
//
// --lods gives the sphere a chain of two coarser levels (12 and 6
// segments) with errors of 10 and 12.5 cm, so at the default size and
// altitude the instances (and the entities, by the same rule) draw all
// three levels by distance (a smaller image: coarser ones); the GPU path
// then chooses a level per instance in its compute pass and draws one
// group per level. A row after each count gives the instances the GPU
// path drew at each level (read back).
//
//   bench_instances [--frames N] [--counts 10000,100000,1000000] [--size WxH] [--skip-entities-over N]
//                   [--altitude M]   (lower: fewer instances in view, culling weighs more)
//                   [--lods]
#include <QCoreApplication>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/gpu_bytes.h"
#include "mesh/primitives.h"
#include "render/instanced_source.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/scene_state.h"
#include "tests/common/scene_parts.h"
#include "sequencer/camera_path.h"

using namespace hs;

namespace {

constexpr scene::AssetId kSphere = 2;
constexpr double kSpacing = 2.0;

struct Options {
  int frames = 5, width = 1280, height = 720;
  std::vector<double> counts = {1e4, 1e5, 1e6};
  size_t entitiesUpTo = 1000000;  // (a) above this count is skipped
  double altitude = 60.0;         // the camera's height over the field (m)
  bool lods = false;              // the sphere with a chain of three levels
};

scene::SceneState baseScene(const Options& o) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.shadows = false;
  s.settings.ambientIntensity = 0.3f;
  test::addMeshAsset(s, kSphere, "Sphere", mesh::uvSphere(0.5f, 32, 32), {0.3f, 0.6f, 0.25f});
  if (o.lods) {
    scene::MeshAsset& a = s.assets.at(kSphere);
    for (int k = 0; k < 2; ++k) {
      mesh::MeshData m = mesh::uvSphere(0.5f, k == 0 ? 12 : 6, k == 0 ? 12 : 6);
      scene::MeshLod lod;
      lod.contentHash = mesh::contentHash(m);
      lod.triangles = m.triangleCount();
      lod.hausdorff = k == 0 ? 0.10 : 0.125;
      lod.data = std::make_shared<const mesh::MeshData>(std::move(m));
      a.lods.push_back(std::move(lod));
    }
  }
  test::addSun(s, 1, {50, 0, -35});
  return s;
}

// The field: `n` places on a square grid centred on the origin.
std::vector<glm::dvec3> field(size_t n) {
  const size_t side = size_t(std::ceil(std::sqrt(double(n))));
  std::vector<glm::dvec3> out;
  out.reserve(n);
  for (size_t i = 0; i < n; ++i)
    out.emplace_back((double(i % side) - 0.5 * double(side)) * kSpacing, (double(i / side) - 0.5 * double(side)) * kSpacing,
                     0.5);
  return out;
}

render::InstanceSet instanceSet(const std::vector<glm::dvec3>& places) {
  render::InstanceSet set;
  set.types = {render::InstanceType{kSphere}};
  // 128 m cells (the foliage issue's order of size).
  const double cell = 128.0;
  std::map<std::pair<long, long>, uint16_t> cells;
  for (size_t i = 0; i < places.size(); ++i) {
    const auto key = std::make_pair(long(std::floor(places[i].x / cell)), long(std::floor(places[i].y / cell)));
    auto [it, added] = cells.emplace(key, uint16_t(set.cells.size()));
    if (added) set.cells.emplace_back(double(key.first) * cell, double(key.second) * cell, 0.0);
    const glm::quat q = glm::angleAxis(float(i % 360) * 0.0174533f, glm::vec3(0, 0, 1));
    set.instances.push_back(
        render::packInstance(glm::vec3(places[i] - set.cells[it->second]), q, 1.0f, 0, it->second, uint32_t(i)));
  }
  set.entity = 100;
  return set;
}

render::RenderView topView(const Options& o) {
  render::RenderView v;
  v.width = o.width;
  v.height = o.height;
  v.fovY = glm::radians(60.0);
  v.eye = {0.3, 0.2, o.altitude};
  v.orientation = sequencer::lookRotation(glm::dvec3(0.0, 0.001, -1.0));
  return v;
}

struct Row {
  std::string mode;
  size_t count = 0;
  double frameMs = 0.0, cpuMs = 0.0;
  size_t drawCalls = 0;
  int64_t visible = -1;
  double bytesPerInstance = 0.0;
  bool skipped = false;
};

Row measure(render::OffscreenRenderer& r, const scene::SceneState& s, const std::shared_ptr<render::InstancedSource>& src,
            const std::string& mode, size_t count, size_t baselineBytes, const Options& o) {
  Row row{mode, count};
  r.renderer().setDrawSources(src ? std::vector<std::shared_ptr<render::DrawSource>>{src}
                                  : std::vector<std::shared_ptr<render::DrawSource>>{});
  const render::RenderView v = topView(o);
  r.renderOnly(s, v);  // uploads, programs
  r.renderOnly(s, v);
  std::vector<double> wall, cpu;
  render::FrameStats st;
  for (int f = 0; f < o.frames; ++f) {
    const double t0 = bench::nowSeconds();
    st = r.renderOnly(s, v);
    wall.push_back(1000.0 * (bench::nowSeconds() - t0));
    cpu.push_back(st.cpuMs);
  }
  row.frameMs = bench::median(wall);
  row.cpuMs = bench::median(cpu);
  row.drawCalls = st.drawCalls;
  row.visible = src ? src->lastVisible() : int64_t(st.instancesDrawn);
  const size_t bytes = bench::registryBytes(r.renderer());
  row.bytesPerInstance = double(bytes - std::min(bytes, baselineBytes)) / double(count);
  r.renderer().setDrawSources({});
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) o.frames = std::atoi(argv[++i]);
    else if (a == "--counts" && i + 1 < argc) o.counts = bench::numberList(argv[++i]);
    else if (a == "--size" && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else if (a == "--skip-entities-over" && i + 1 < argc) o.entitiesUpTo = size_t(std::atof(argv[++i]));
    else if (a == "--altitude" && i + 1 < argc) o.altitude = std::atof(argv[++i]);
    else if (a == "--lods") o.lods = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_instances [--frames N] [--counts A,B,C] [--size WxH] [--skip-entities-over N] "
                   "[--altitude M] [--lods]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_instances: %s\n", error.c_str());
    return 1;
  }
  std::printf("# bench_instances: %dx%d, camera %.0f m above the field, %d frames (median), %s%s\n# %s\n# %s\n\n",
              o.width, o.height, o.altitude, o.frames, o.lods ? "3 LOD levels, " : "", r.glDescription().c_str(),
              bench::threadsText().c_str(), bench::loadAverageLine().c_str());
  std::printf("| instances | way | frame ms | CPU ms | draw calls | visible | GPU bytes / instance | frame vs (a) |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|\n");
  const scene::SceneState base = baseScene(o);
  r.renderOnly(base, topView(o));
  const size_t baseline = bench::registryBytes(r.renderer());
  for (double countD : o.counts) {
    const size_t count = size_t(countD);
    const std::vector<glm::dvec3> places = field(count);
    std::vector<Row> rows;
    if (count <= o.entitiesUpTo) {
      scene::SceneState withEntities = base;
      for (size_t i = 0; i < count; ++i) {
        scene::Entity e;
        e.id = 1000 + i;
        e.name = "i";
        e.mesh = scene::MeshInstance{kSphere};
        e.transform.translation = places[i];
        e.transform.rotation = glm::angleAxis(double(i % 360) * 0.0174533, glm::dvec3(0, 0, 1));
        withEntities.entities.emplace(e.id, std::move(e));
        withEntities.roots.push_back(1000 + i);
      }
      rows.push_back(measure(r, withEntities, nullptr, "(a) entities", count, baseline, o));
    } else {
      rows.push_back(Row{"(a) entities", count});
      rows.back().skipped = true;
    }
    const render::InstanceSet set = instanceSet(places);
    std::vector<int64_t> byLevel;
    for (auto [culling, name] : {std::pair{render::InstancedSource::Culling::Cpu, "(b) cpu-culled instanced"},
                                 std::pair{render::InstancedSource::Culling::Gpu, "(c) gpu-culled indirect"}}) {
      auto src = std::make_shared<render::InstancedSource>("bench_instances", culling);
      src->setInstances(set);
      rows.push_back(measure(r, base, src, name, count, baseline, o));
      byLevel = src->lastVisibleByLevel();
    }
    for (const Row& row : rows) {
      if (row.skipped) {
        std::printf("| %zu | %s | skipped (--skip-entities-over) | | | | | |\n", row.count, row.mode.c_str());
        continue;
      }
      const double vsA = rows[0].skipped ? 0.0 : row.frameMs / rows[0].frameMs;
      std::printf("| %zu | %s | %.1f | %.1f | %zu | %lld | %.1f | %s |\n", row.count, row.mode.c_str(), row.frameMs,
                  row.cpuMs, row.drawCalls, static_cast<long long>(row.visible), row.bytesPerInstance,
                  rows[0].skipped ? "-" : (std::to_string(vsA).substr(0, 5) + "x").c_str());
      std::fflush(stdout);
    }
    if (o.lods) {
      std::string levels;
      for (size_t l = 0; l < byLevel.size(); ++l)
        levels += (l ? ", " : "") + std::string("level ") + std::to_string(l) + ": " + std::to_string(byLevel[l]);
      std::printf("| %zu | (c) drawn by level | %s | | | | | |\n", count, levels.c_str());
    }
  }
  return 0;
}
