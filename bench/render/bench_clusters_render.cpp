// bench_clusters_render: a huge scan drawn from its cluster hierarchy
// (render/cluster_source.h) against the same scan drawn whole (what the
// per-instance LOD chain draws when the camera stands inside the tile:
// level 0 everywhere), side by side in one run. For generated scan tiles
// (bench/decimate/scan_terrain.h: rolling ground, rock pillars, holes) of
// the given sizes: the hierarchy's build time and pages, then along a low
// flight over the tile, per frame: triangles and clusters drawn, pages
// resident and drawn, GPU pool memory against the budget, the cut's time
// (with the page uploads; each frame waits for a whole cut, as exports do),
// the frame's wall time for both, and the image difference to the whole
// scan's (share of pixels differing by more than 16/255, largest channel
// difference): the approximation's error against its run time.
//
//   bench_clusters_render [--sizes 0.5,2] [--size WxH] [--frames N] [--budget-mb M] [--estimate] [--valley]
//                         [--images DIR]
// (--estimate: the groups' quadric estimates instead of certified errors,
// several times faster to build. --valley: a valley of 1M-triangle tiles
// (bench/decimate/scan_valley.h) built out of core, tile by tile
// (meshproc/cluster_build_streamed.h), pages read from the build's page
// file; the whole scan for the comparison is the tiles merged in memory.)
#include <QCoreApplication>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/tile_merge.h"
#include "scan_terrain.h"  // bench/decimate: the generated scan tiles
#include "scan_valley.h"
#include "render/offscreen_renderer.h"
#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"
#include "sequencer/camera_path.h"
#include "tests/common/image_compare.h"

using namespace hs;

namespace {

test::Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  std::vector<double> sizes = {0.5, 2.0};
  int width = 960, height = 540, frames = 6;
  double budgetMb = 1024.0;
  bool certify = true, valley = false;
  std::string imageDir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sizes" && i + 1 < argc) sizes = bench::numberList(argv[++i]);
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) != 2) return 2;
    else if (a == "--frames" && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--budget-mb" && i + 1 < argc) budgetMb = std::atof(argv[++i]);
    else if (a == "--estimate") certify = false;
    else if (a == "--valley") valley = true;
    else if (a == "--images" && i + 1 < argc) imageDir = argv[++i];
  }
  render::OffscreenRenderer clustered, whole;
  std::string error;
  if (!clustered.initialize(error) || !whole.initialize(error)) {
    std::fprintf(stderr, "bench_clusters_render: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_clusters_render: %dx%d, 50 degrees, 1 px, GPU budget %.0f MiB, errors %s; %s; %s\n", width,
              height, budgetMb, certify ? "certified" : "estimated", bench::threadsText().c_str(),
              bench::loadAverageLine().c_str());
  std::printf("GL: %s\n", clustered.glDescription().c_str());

  for (double millions : sizes) {
    const int n = int(std::sqrt(millions * 1e6 / 2.0));
    double size = 1000.0 * std::sqrt(millions / 0.5);
    mesh::MeshData tile;
    mesh::ClusterOptions o;
    o.certifyErrors = certify;
    scene::ClusterBuild b;
    double buildSeconds = 0.0;
    bench::ValleyLayout layout;
    if (valley) {
      layout = bench::valleyLayout(millions, 1.0);
      std::vector<mesh::MeshData> tiles;
      for (int tj = 0; tj < layout.tilesY; ++tj)
        for (int ti = 0; ti < layout.tilesX; ++ti) tiles.push_back(bench::valleyTile(layout, ti, tj));
      std::vector<const mesh::MeshData*> ptrs;
      for (const auto& t : tiles) ptrs.push_back(&t);
      mesh::MeshTileSource source(ptrs);
      mesh::StreamedClusterOptions so;
      so.clusters = o;
      const auto built = std::chrono::steady_clock::now();
      b = scene::buildClusterAssetStreamed(source, so, scene::kClusterProxyTriangles, nullptr, nullptr, error);
      buildSeconds = secondsSince(built);
      if (!b.clusters) {
        std::fprintf(stderr, "bench_clusters_render: %s\n", error.c_str());
        return 1;
      }
      tile = mesh::mergeTiles(std::move(tiles), 1e-3);
      mesh::computeVertexNormals(tile);
      size = layout.tilesX * layout.tileSize;
    } else {
      tile = bench::scanTerrain(n, size);
      const auto built = std::chrono::steady_clock::now();
      b = scene::buildClusterAsset(tile, o, scene::kClusterProxyTriangles);
      buildSeconds = secondsSince(built);
    }
    const scene::ClusterAsset& c = *b.clusters;
    std::printf("\n%zu triangles (%.0f m tile): hierarchy of %zu levels, %zu clusters, %u pages (%.1f MiB) built in "
                "%.1f s, peak RSS so far %.0f MiB\n",
                tile.triangleCount(), size, c.levels(), c.index.clusters.size(), c.index.pageCount,
                double(c.totalPageBytes()) / 1048576.0, buildSeconds, double(bench::statusKiB("VmHWM:")) / 1024.0);

    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.clusterGpuBudgetMb = budgetMb;
    scene::MeshAsset a;
    a.id = 1;
    a.name = "tile";
    a.contentHash = mesh::contentHash(b.proxy);
    a.data = std::make_shared<const mesh::MeshData>(std::move(b.proxy));
    a.clustersHash = b.clustersHash;
    a.clusters = b.clusters;
    scene::MeshAsset w;
    w.id = 2;
    w.name = "whole";
    w.contentHash = mesh::contentHash(tile);
    w.data = std::make_shared<const mesh::MeshData>(std::move(tile));
    s.assets.emplace(1, a);
    s.assets.emplace(2, w);
    scene::Entity e;
    e.id = 1;
    e.name = "Tile";
    e.mesh = scene::MeshInstance{1};
    s.entities.emplace(e.id, e);
    s.roots.push_back(e.id);
    scene::Entity sun;
    sun.id = 2;
    sun.name = "Sun";
    sun.light = scene::Light{};
    sun.transform.rotation = glm::angleAxis(glm::radians(40.0), glm::dvec3(1, 0, 0));
    s.entities.emplace(sun.id, sun);
    s.roots.push_back(sun.id);
    // Each mesh where its origin puts it (as an import places it): the
    // streamed build's frame is centred on the scan, the merged tiles' not.
    s.entities.at(1).transform.translation = a.data->origin;
    scene::SceneState wholeScene = s;
    wholeScene.entities.at(1).mesh = scene::MeshInstance{2};
    wholeScene.entities.at(1).transform.translation = w.data->origin;

    std::printf("%5s %10s %8s %8s %8s %10s %8s %10s %10s %7s %10s %8s\n", "frame", "triangles", "clusters",
                "resident", "drawn", "GPU MiB", "cut ms", "frame ms", "whole tri", "whole ms", "differ %", "max");
    for (int f = 0; f < frames; ++f) {
      // A low flight across the tile, 40 m over its middle, looking ahead and down.
      const double t = frames > 1 ? double(f) / double(frames - 1) : 0.5;
      // The valley: 40 m over the ground along its length, a third of the way up.
      const glm::dvec3 eye = valley ? layout.pointAt(0.1 + 0.6 * t, 0.3, 40.0)
                                    : glm::dvec3(-0.35 * size + 0.7 * size * t, -0.1 * size, 60.0);
      render::RenderView v;
      v.eye = eye;
      v.orientation = sequencer::lookRotation(glm::dvec3(0.3, 1.0, -0.35));
      v.fovY = glm::radians(50.0);
      v.width = width;
      v.height = height;
      v.nearClip = 0.1;
      v.farClip = 20000.0;
      render::FrameStats cs, ws;
      auto t0 = std::chrono::steady_clock::now();
      const hs::Image ci = clustered.render(s, v, false, &cs);
      const double clusterMs = secondsSince(t0) * 1e3;
      t0 = std::chrono::steady_clock::now();
      const hs::Image wi = whole.render(wholeScene, v, false, &ws);
      const double wholeMs = secondsSince(t0) * 1e3;
      const test::CompareResult cmp = test::compareImages(toTest(ci), toTest(wi), 16);
      if (!imageDir.empty()) {  // --images DIR: both pictures of each frame, to see where they differ
        const std::string stem = imageDir + "/" + std::to_string(int(std::lround(millions))) + "M_frame" + std::to_string(f);
        test::writePng(stem + "_clusters.png", toTest(ci));
        test::writePng(stem + "_whole.png", toTest(wi));
      }
      std::printf("%5d %10zu %8zu %8zu %8zu %10.1f %8.1f %10.0f %10zu %7.0f %10.3f %8d%s\n", f, cs.trianglesDrawn,
                  cs.clusters.clusters, cs.clusters.pagesResident, cs.clusters.pagesDrawn,
                  double(cs.clusters.gpuBytes) / 1048576.0, cs.clusters.cutMs, clusterMs, ws.trianglesDrawn, wholeMs,
                  100.0 * cmp.differingShare, cmp.maxChannelDiff, cs.clusters.complete ? "" : " (not whole)");
    }
  }
  return 0;
}
