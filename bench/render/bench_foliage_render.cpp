// bench_foliage_render: a forest of 100k, 1M and 10M generated trees
// (foliage/plants.h: a conifer and a broadleaf with the project's LOD
// chains, scene/foliage_ops.h makePlantAsset, the demo's sizes) on a flat
// ground, drawn by the instanced source the document's foliage draws
// through (render/instanced_source.h, GPU culling), two ways:
//   culled    the compute passes choose each instance's level from the
//             LOD view (mesh LOD bound --lod-pixels, 1 px by default),
//             drop it beyond the type's cull distance (400 m, 60 m fade)
//             and test its sphere against the view: what the editor and
//             the export do
//   full      every instance at level 0, no cull distance, no view test
//             (InstancedSource::setViewCulling(false)): the naive way
// The trees stand on a jittered 8 m grid, so the field grows with the
// count (360 m, 2.5 km, 8 km, 25 km across for 2k, 100k, 1M, 10M) while
// the camera, 6 m above the ground at the field's south edge looking north
// over it at a grazing angle, sees about the same forest (the cull
// distance, 400 m: a CPU rasteriser draws a few million triangles a
// second, so a frame of more is minutes): what grows with the count is the
// culling pass and memory. Above kMaxInstancesPerSource (about 4.2M) the
// trees are split into several sources, as the document's foliage is. No
// sun shadow (each cascade would draw the field again: the cascades'
// caster count is a separate question).
//
// Columns: frame time (wall, the GPU waited for; median), CPU time of the
// render call (FrameStats::cpuMs), instances and triangles the view drew
// (the GPU's counts, read back a frame later), GPU bytes per instance (the
// registry's total against the scene without trees, over the count), the
// process's resident memory after the row, and frame time against the
// full way (the ratio). A "drawn by level" row gives the culled way's
// instances per level; a "cull pass" row the compute passes on their own
// (FrameStats per-pass GPU and CPU time, median of the timed frames, which
// carry RenderOptions::passTimings; they include the level choice). The full way
// is skipped where its frame would pass --cap seconds, guessed from its
// triangles at the last measured full frame's triangle rate (a frame of
// 100k trees at full detail is minutes on a CPU rasteriser): the row says
// so, and the ratio is then against that guess. The 2k field is there so
// that one full frame is measured (and gives the rate). Rows whose first
// frame took over 2 s time one frame, not --frames.
//
//   bench_foliage_render [--counts 2000,100000,1000000,10000000] [--frames N] [--size WxH] [--cap S]
//                        [--lod-pixels P]   (the culled way's LOD bound; 1: the project's default)
//
// With --lod-table B1,B2,... (e.g. 1,2,4,8,16) it prints instead the error
// against run time table of the LOD chain and the octahedral impostors
// (render/impostor_atlas.h): the field of --table-count trees (2000) at
// each bound, impostors off and on, against full detail (see lodTable).
#include <QCoreApplication>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/gpu_bytes.h"
#include "foliage/plants.h"
#include "mesh/primitives.h"
#include "render/instanced_source.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/demo_foliage.h"
#include "scene/foliage_ops.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"
#include "sequencer/camera_path.h"
#include "tests/common/plant_asset.h"
#include "tests/common/scene_parts.h"

using namespace hs;

namespace {

constexpr scene::AssetId kGround = 1, kPine = 2, kPlane = 3;
constexpr double kSpacing = 8.0, kCell = 128.0;
constexpr double kCullDistance = 400.0, kFade = 60.0;

struct Options {
  int frames = 3, width = 1920, height = 1080;
  std::vector<double> counts = {2e3, 1e5, 1e6, 1e7};
  double capSeconds = 60.0;
  double lodPixels = 1.0;    // the culled way's mesh LOD bound (settings.meshLodErrorPixels; the project's default)
  // --lod-table: the error against run time table instead (the bounds of
  // its rows; empty: the count table), over a field of tableCount trees.
  std::vector<double> lodTable;
  size_t tableCount = 2000;
};

// The demo's pine and plane tree (scene::demoPlants), a few thousand
// triangles at full detail, with their LOD chains and leaf materials.
void addPlants(scene::SceneState& s, std::vector<size_t>& fullTriangles) {
  const std::vector<scene::DemoPlant> plants = scene::demoPlants();
  for (auto [id, plant] : {std::pair{kPine, plants[0]}, std::pair{kPlane, plants[1]}}) {
    test::addPlantAsset(s, id, plant.asset, plant.params, true);
    fullTriangles.push_back(s.assets.at(id).data->triangleCount());
  }
}

double fieldSide(size_t n) { return std::ceil(std::sqrt(double(n))) * kSpacing; }

// `n` trees on a jittered grid centred on the origin, in 128 m cells; every
// other tree (by a hash, not a pattern) a plane tree. Whole rows of the grid
// per set, at most kMaxInstancesPerSource each (one source culls no more:
// instanced_source.h), as foliage_instances.h splits the document's.
std::vector<render::InstanceSet> forest(size_t n, bool culled, bool impostors = false) {
  render::InstanceSet proto;
  for (scene::AssetId mesh : {kPine, kPlane}) {
    render::InstanceType t;
    t.mesh = mesh;
    t.impostor = impostors;
    t.cullDistance = culled ? float(kCullDistance) : 0.0f;
    t.fadeLength = culled ? float(kFade) : 0.0f;
    t.windResponse = 1.0f;
    proto.types.push_back(t);
  }
  proto.entity = 100;
  const size_t side = size_t(std::ceil(std::sqrt(double(n))));
  const size_t rowsPerSet = render::kMaxInstancesPerSource / side;
  const double half = 0.5 * double(side) * kSpacing;
  const size_t cellsPerSide = size_t(std::ceil(2.0 * half / kCell));
  std::vector<render::InstanceSet> sets;
  std::vector<int> cellIndex;
  std::mt19937 rng(2026);
  std::uniform_real_distribution<float> jitter(-0.4f * float(kSpacing), 0.4f * float(kSpacing)), unit(0.0f, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    if (i % (rowsPerSet * side) == 0) {
      sets.push_back(proto);
      sets.back().instances.reserve(std::min(n - i, rowsPerSet * side));
      cellIndex.assign(cellsPerSide * cellsPerSide, -1);
    }
    render::InstanceSet& set = sets.back();
    const double x = (double(i % side) + 0.5) * kSpacing - half + double(jitter(rng));
    const double y = (double(i / side) + 0.5) * kSpacing - half + double(jitter(rng));
    const size_t cx = std::min(cellsPerSide - 1, size_t((x + half) / kCell));
    const size_t cy = std::min(cellsPerSide - 1, size_t((y + half) / kCell));
    int& c = cellIndex[cy * cellsPerSide + cx];
    if (c < 0) {
      c = int(set.cells.size());
      set.cells.emplace_back(double(cx) * kCell - half, double(cy) * kCell - half, 0.0);
    }
    const glm::dvec3 origin = set.cells[size_t(c)];
    const glm::quat yaw = glm::angleAxis(6.2831853f * unit(rng), glm::vec3(0, 0, 1));
    const float scale = 0.7f + 0.6f * unit(rng);
    const uint16_t type = uint16_t(unit(rng) < 0.5f ? 0 : 1);
    set.instances.push_back(render::packInstance(glm::vec3(glm::dvec3(x, y, 0.0) - origin), yaw, scale, type,
                                                 uint16_t(c), uint32_t(i)));
  }
  return sets;
}

// The trees' assets and a sun, made once (the LOD chains take a moment),
// with a placeholder ground (asset and material 1) that ground() resizes.
scene::SceneState plantScene(std::vector<size_t>& fullTriangles) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.shadows = false;
  test::addMeshAsset(s, kGround, "Ground", mesh::gridPlane(100.0f, 8), {0.35f, 0.4f, 0.25f});
  test::addMeshEntity(s, 1, "Ground", kGround);
  test::addSun(s, 2, {50, 0, -35});
  addPlants(s, fullTriangles);
  return s;
}

// The plant scene with a ground under a field `side` metres across, the
// mesh LOD bound `lodPixels` (0: level 0 everywhere).
scene::SceneState sceneFor(const scene::SceneState& plants, double side, double lodPixels) {
  scene::SceneState s = plants;
  s.settings.meshLodErrorPixels = lodPixels;
  scene::MeshAsset& g = s.assets.at(kGround);
  mesh::MeshData m = mesh::gridPlane(float(side + 100.0), 8);
  g.contentHash = mesh::contentHash(m);
  g.data = std::make_shared<const mesh::MeshData>(std::move(m));
  return s;
}

// 6 m above the ground, 30 m inside the field's south edge, looking north
// and 3 degrees down: the forest to the horizon (and the cull distance).
render::RenderView grazing(const Options& o, double side) {
  render::RenderView v;
  v.width = o.width;
  v.height = o.height;
  v.fovY = glm::radians(50.0);
  v.eye = {0.0, -0.5 * side + 30.0, 6.0};
  v.orientation = sequencer::lookRotation(glm::dvec3(0.0, 1.0, -std::tan(glm::radians(3.0))));
  return v;
}

struct Row {
  double frameMs = 0.0, cpuMs = 0.0, cullGpuMs = -1.0, cullCpuMs = 0.0;
  int64_t instances = -1, triangles = -1;
  std::vector<int64_t> byLevel;
  int timedFrames = 0;
  size_t sources = 0;
  double bytesPerInstance = 0.0, rssMb = 0.0;
};

Row measure(render::OffscreenRenderer& r, const scene::SceneState& s, const std::vector<render::InstanceSet>& sets,
            bool culled, const render::RenderView& v, double side, int frames) {
  // The baseline holds the trees' meshes too: one tree of each type drawn.
  const size_t baseline = [&] {
    render::InstanceSet two = sets[0];
    two.instances.clear();
    for (uint16_t t = 0; t < 2; ++t)
      two.instances.push_back(render::packInstance(
          glm::vec3(glm::dvec3(10.0 * t, -0.5 * side + 60.0, 0.0) - two.cells[0]), glm::quat(1, 0, 0, 0), 1.0f, t, 0, t));
    auto few = std::make_shared<render::InstancedSource>("foliage", render::InstancedSource::Culling::Gpu);
    few->setInstances(std::move(two));
    r.renderer().setDrawSources({few});
    r.renderOnly(s, v);
    r.renderOnly(s, v);
    r.renderer().setDrawSources({});
    return bench::registryBytes(r.renderer());
  }();
  // One source a set, named as foliage_sources.h names the document's.
  std::vector<std::shared_ptr<render::InstancedSource>> sources;
  std::vector<std::shared_ptr<render::DrawSource>> draw;
  size_t count = 0;
  for (size_t k = 0; k < sets.size(); ++k) {
    sources.push_back(std::make_shared<render::InstancedSource>("foliage" + (k ? std::to_string(k) : std::string()),
                                                                render::InstancedSource::Culling::Gpu));
    sources.back()->setInstances(sets[k]);
    sources.back()->setViewCulling(culled);
    draw.push_back(sources.back());
    count += sets[k].instances.size();
  }
  r.renderer().setDrawSources(draw);
  Row row;
  render::RenderOptions timed;
  // Per-pass timestamps in every timed frame (they wait for each pass: on
  // a CPU rasteriser, where the frame is synchronous anyway, a few ms in
  // tens of seconds), so one frame gives both the frame and the pass.
  timed.passTimings = true;
  const double t0 = bench::nowSeconds();
  r.renderOnly(s, v, timed);  // uploads, programs
  const double firstSeconds = bench::nowSeconds() - t0;
  // A slow frame (seconds on a CPU rasteriser): one timed frame.
  if (firstSeconds > 2.0) frames = 1;
  std::vector<double> wall, cpu, cullGpu, cullCpu;
  for (int f = 0; f < frames; ++f) {
    const double t = bench::nowSeconds();
    const render::FrameStats st = r.renderOnly(s, v, timed);
    wall.push_back(1000.0 * (bench::nowSeconds() - t));
    cpu.push_back(st.cpuMs);
    double g = 0.0, c = 0.0;  // every source's "<name>_cull" pass
    for (const render::PassStats& p : st.passes)
      if (p.name.size() > 5 && p.name.compare(p.name.size() - 5, 5, "_cull") == 0 && p.name.rfind("foliage", 0) == 0) {
        g += p.gpuMs;
        c += p.cpuMs;
      }
    cullGpu.push_back(g);
    cullCpu.push_back(c);
  }
  row.frameMs = bench::median(wall);
  row.cpuMs = bench::median(cpu);
  row.cullGpuMs = bench::median(cullGpu);
  row.cullCpuMs = bench::median(cullCpu);
  row.timedFrames = frames;
  row.instances = row.triangles = 0;
  for (const auto& src : sources) {
    row.instances += src->lastVisible();
    row.triangles += src->lastTrianglesDrawn();
    const std::vector<int64_t> levels = src->lastVisibleByLevel();
    if (row.byLevel.size() < levels.size()) row.byLevel.resize(levels.size(), 0);
    for (size_t l = 0; l < levels.size(); ++l) row.byLevel[l] += levels[l];
  }
  row.sources = sources.size();
  const size_t bytes = bench::registryBytes(r.renderer());
  row.bytesPerInstance = double(bytes - std::min(bytes, baseline)) / double(count);
  row.rssMb = bench::statusKiB("VmRSS:") / 1024.0;
  r.renderer().setDrawSources({});
  return row;
}

// The error against run time table (--lod-table): the field of
// o.tableCount trees, culled, at each mesh LOD bound of the list, without
// and with impostors, against the same frame at full detail (bound 0:
// level 0 everywhere): frame time, instances per level (the impostor is
// the level after the chain), triangles, and the image error: the share
// of pixels of the 8-bit output any channel of which differs by more than
// 8 (of 255) from full detail, and the mean absolute difference over all
// pixels and channels.
int lodTable(render::OffscreenRenderer& r, const scene::SceneState& plants, const Options& o) {
  const double side = fieldSide(o.tableCount);
  const render::RenderView v = grazing(o, side);
  auto frame = [&](double bound, bool impostors, Row& row) {
    const scene::SceneState s = sceneFor(plants, side, bound);
    row = measure(r, s, forest(o.tableCount, true, impostors), true, v, side, o.frames);
    std::vector<std::shared_ptr<render::DrawSource>> draw;
    for (const render::InstanceSet& set : forest(o.tableCount, true, impostors)) {
      auto src = std::make_shared<render::InstancedSource>("foliage", render::InstancedSource::Culling::Gpu);
      src->setInstances(set);
      draw.push_back(src);
    }
    r.renderer().setDrawSources(draw);
    Image img = r.render(s, v);
    r.renderer().setDrawSources({});
    return img;
  };
  Row fullRow;
  const Image full = frame(0.0, false, fullRow);
  std::printf("| LOD bound px | impostors | frame ms | frame vs full detail | drawn by level (last: impostor) | "
              "triangles drawn | pixels off (> 8/255) | mean abs difference (/255) |\n");
  std::printf("|---:|---|---:|---:|---|---:|---:|---:|\n");
  auto levels = [](const Row& row) {
    std::string t;
    for (size_t l = 0; l < row.byLevel.size(); ++l)
      t += (l ? ", " : "") + std::to_string(l) + ": " + std::to_string(row.byLevel[l]);
    return t;
  };
  std::printf("| 0 (full detail) | - | %.1f | 1x | %s | %lld | 0 | 0 |\n", fullRow.frameMs, levels(fullRow).c_str(),
              static_cast<long long>(fullRow.triangles));
  std::fflush(stdout);
  for (double bound : o.lodTable)
    for (bool impostors : {false, true}) {
      Row row;
      const Image img = frame(bound, impostors, row);
      size_t off = 0;
      double sum = 0.0;
      for (size_t p = 0; p < img.pixelCount(); ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
          const int d = std::abs(int(img.rgba8[p * 4 + size_t(c)]) - int(full.rgba8[p * 4 + size_t(c)]));
          worst = std::max(worst, d);
          sum += d;
        }
        off += worst > 8;
      }
      std::printf("| %g | %s | %.1f | %.3fx | %s | %lld | %.2f %% | %.3f |\n", bound, impostors ? "on" : "off",
                  row.frameMs, row.frameMs / fullRow.frameMs, levels(row).c_str(),
                  static_cast<long long>(row.triangles), 100.0 * double(off) / double(img.pixelCount()),
                  sum / (3.0 * double(img.pixelCount())));
      std::fflush(stdout);
    }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) o.frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--counts" && i + 1 < argc) o.counts = bench::numberList(argv[++i]);
    else if (a == "--size" && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else if (a == "--cap" && i + 1 < argc) o.capSeconds = std::atof(argv[++i]);
    else if (a == "--lod-pixels" && i + 1 < argc) o.lodPixels = std::atof(argv[++i]);
    else if (a == "--lod-table" && i + 1 < argc) o.lodTable = bench::numberList(argv[++i]);
    else if (a == "--table-count" && i + 1 < argc) o.tableCount = size_t(std::atof(argv[++i]));
    else {
      std::fprintf(stderr, "usage: bench_foliage_render [--counts A,B,C] [--frames N] [--size WxH] [--cap S] [--lod-pixels P]\n"
                           "                            [--lod-table B1,B2,.. [--table-count N]]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_foliage_render: %s\n", error.c_str());
    return 1;
  }
  std::vector<size_t> fullTriangles;
  const double t0 = bench::nowSeconds();
  const scene::SceneState plants = plantScene(fullTriangles);
  std::printf("# bench_foliage_render: %dx%d, trees on a %.0f m grid, camera 6 m up at the south edge looking north, "
              "%d frames (median)\n# plants: pine %zu and plane tree %zu triangles at level 0 (made with their LOD "
              "chains in %.1f s); cull distance %.0f m, fade %.0f m, LOD bound %.1f px\n# %s\n# %s\n# %s\n\n",
              o.width, o.height, kSpacing, o.frames, fullTriangles[0], fullTriangles[1], bench::nowSeconds() - t0,
              kCullDistance, kFade, o.lodPixels, r.glDescription().c_str(), bench::threadsText().c_str(),
              bench::loadAverageLine().c_str());
  if (!o.lodTable.empty()) return lodTable(r, plants, o);
  std::printf("| instances | way | frame ms | CPU ms | instances drawn | triangles drawn | GPU bytes / instance | "
              "RSS MB | frame vs full |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);
  double fullRate = 0.0;  // triangles a second of the last full frame measured
  for (double countD : o.counts) {
    const size_t count = size_t(countD);
    const double side = fieldSide(count);
    const render::RenderView v = grazing(o, side);
    Row culled, full;
    size_t fullTris = 0;  // what the full way would draw: every tree at level 0
    {
      const scene::SceneState s = sceneFor(plants, side, o.lodPixels);
      const std::vector<render::InstanceSet> sets = forest(count, true);
      for (const render::InstanceSet& set : sets)
        for (const render::GpuInstance& g : set.instances) fullTris += fullTriangles[g.typeAndCell & 0xFFFFu];
      culled = measure(r, s, sets, true, v, side, o.frames);
    }
    // The full frame's time guessed from the triangle rate of the last full
    // frame measured (else this count's culled frame, whose coarse levels
    // draw fewer triangles a second: an overestimate): a CPU rasteriser is
    // bound by its vertex work, about linear in the triangles. Where the
    // guess passes the cap, the full way is not run.
    const double trianglesPerSecond =
        fullRate > 0.0 ? fullRate : double(culled.triangles) / (1e-3 * culled.frameMs);
    const double fullEstimateS = double(fullTris) / trianglesPerSecond;
    const bool fullSkipped = fullEstimateS > o.capSeconds;
    if (!fullSkipped) {
      const scene::SceneState s = sceneFor(plants, side, 0.0);
      full = measure(r, s, forest(count, false), false, v, side, o.frames);
      fullRate = double(full.triangles) / (1e-3 * full.frameMs);
    }
    auto print = [&](const char* way, const Row& row) {
      char ratio[48] = "";
      if (!fullSkipped) std::snprintf(ratio, sizeof ratio, "%.4fx", row.frameMs / full.frameMs);
      else std::snprintf(ratio, sizeof ratio, "~%.5fx (estimate)", row.frameMs / (1e3 * fullEstimateS));
      std::printf("| %zu | %s (%zu source%s, %d frame%s) | %.1f | %.1f | %lld | %lld | %.1f | %.0f | %s |\n", count, way,
                  row.sources, row.sources == 1 ? "" : "s", row.timedFrames, row.timedFrames == 1 ? "" : "s",
                  row.frameMs, row.cpuMs,
                  static_cast<long long>(row.instances), static_cast<long long>(row.triangles), row.bytesPerInstance,
                  row.rssMb, ratio);
    };
    auto levels = [&](const Row& row) {
      std::string t;
      for (size_t l = 0; l < row.byLevel.size(); ++l)
        t += (l ? ", " : "") + std::to_string(l) + ": " + std::to_string(row.byLevel[l]);
      return t;
    };
    print("culled: GPU culling + LOD", culled);
    std::printf("| %zu | culled: drawn by level | %s | | | | | | |\n", count, levels(culled).c_str());
    std::printf("| %zu | culled: cull pass alone | %.1f GPU | %.2f | | | | | |\n", count, culled.cullGpuMs,
                culled.cullCpuMs);
    if (fullSkipped) {
      std::printf("| %zu | full: every instance, level 0 | skipped: over %.0f s (estimated %.0f s a frame: %zu "
                  "triangles at %.2f M/s) | | | | | | |\n",
                  count, o.capSeconds, fullEstimateS, fullTris, 1e-6 * trianglesPerSecond);
    } else {
      print("full: every instance, level 0", full);
      std::printf("| %zu | full: cull pass alone | %.1f GPU | %.2f | | | | | |\n", count, full.cullGpuMs,
                  full.cullCpuMs);
    }
    std::fflush(stdout);
  }
  std::printf("\n# peak RSS %.0f MB\n", bench::statusKiB("VmHWM:") / 1024.0);
  return 0;
}
