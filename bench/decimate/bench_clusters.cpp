// The cluster hierarchy (meshproc/cluster_hierarchy.h) on generated scan
// tiles (scan_terrain.h: rolling ground, rock pillars, holes, UV charts):
//  1. the error a group reports against the build's time: the decimator's
//     quadric estimate against a certified Hausdorff bound, and how far a
//     cut's surface really is from the input (sampled) for each;
//  2. per size: build time, peak memory, levels, clusters;
//  3. along a low flight over the tile (1920x1080, 50 degrees, 1 px): the
//     cut's triangles and clusters, its time on the CPU, the largest
//     projected error drawn, against today's per-instance LOD chain, which
//     draws level 0 everywhere because the camera is inside the tile.
// Usage: bench_clusters [--sizes 0.5,2] (millions of triangles)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "meshproc/cluster_hierarchy.h"
#include "meshproc/error_metrics.h"
#include "scan_terrain.h"

using namespace hs;

namespace {

// The tile's ground height near (x, y), from its vertices (a coarse lookup).
float groundNear(const mesh::MeshData& m, float x, float y) {
  float best = 1e30f, z = 0.0f;
  for (size_t i = 0; i < m.positions.size(); i += 97) {
    const glm::vec3& p = m.positions[i];
    const float d = (p.x - x) * (p.x - x) + (p.y - y) * (p.y - y);
    if (d < best) {
      best = d;
      z = p.z;
    }
  }
  return z;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes = {0.5, 2.0};
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--sizes") sizes = bench::numberList(argv[++i]);
  std::printf("bench_clusters: %s, %s\n", bench::threadsText().c_str(), bench::loadAverageLine().c_str());
  const float focal = 540.0f / std::tan(glm::radians(25.0f));  // 1920x1080, 50 degrees vertical

  // 1. The error against the time, on the smallest tile.
  {
    const int n = int(std::sqrt(sizes.front() * 1e6 / 2.0));
    const mesh::MeshData tile = bench::scanTerrain(n, 1000.0);
    std::printf("\n%zu triangles: a group's error from the quadric's estimate or a certified Hausdorff bound\n",
                tile.triangleCount());
    std::printf("%-12s %10s %12s %18s %14s %20s\n", "error", "build s", "cut tris", "cut's error (max)", "measured",
                "clusters over error");
    for (bool certify : {false, true}) {
      mesh::ClusterOptions o;
      o.certifyErrors = certify;
      mesh::ClusterBuildReport rep;
      const mesh::ClusterHierarchy h = mesh::buildClusterHierarchy(tile, o, &rep);
      // A distant view of the whole tile at 1 px: a coarse cut.
      const glm::vec3 eye(500.0f, -2500.0f, 800.0f);
      const std::vector<uint32_t> cut = mesh::selectClusterCut(h, eye, focal, 1.0f);
      const auto [tris, worst] = mesh::summariseCut(h, cut);
      const mesh::ErrorReport e = mesh::measureError(tile, mesh::meshOfCut(h, cut));
      // Each drawn cluster against its own error: its vertices' and its
      // faces' centres' distance to the input (a lower bound of its true
      // distance), how many clusters are further than their error says.
      const mesh::ErrorMeter meter(tile);
      size_t over = 0;
      for (uint32_t id : cut) {
        const mesh::Cluster& c = h.clusters[id];
        double far = 0.0;
        for (uint32_t t = 0; t < c.triangleCount; ++t) {
          glm::dvec3 centre(0.0);
          for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p(h.positions[h.indices[c.firstIndex + t * 3 + k]]);
            centre += p / 3.0;
            far = std::max(far, std::sqrt(meter.originalBvh().closest(p).distanceSq));
          }
          far = std::max(far, std::sqrt(meter.originalBvh().closest(centre).distanceSq));
        }
        over += far > double(c.error) * (1.0 + 1e-4) + 1e-6;
      }
      std::printf("%-12s %10.2f %12zu %16.4f m %12.4f m %10zu of %zu\n", certify ? "certified" : "estimate",
                  rep.seconds, tris, double(worst), e.hausdorff, over, cut.size());
      std::fflush(stdout);
    }
  }

  // 2 and 3. Per size: the build, then the flight.
  for (double millions : sizes) {
    const int n = int(std::sqrt(millions * 1e6 / 2.0));
    const mesh::MeshData tile = bench::scanTerrain(n, 1000.0);
    const size_t before = bench::statusKiB("VmHWM:");
    mesh::ClusterBuildReport rep;
    const mesh::ClusterHierarchy h = mesh::buildClusterHierarchy(tile, {}, &rep);
    const size_t peak = bench::statusKiB("VmHWM:");
    std::printf("\n%zu triangles (%.0f MB as a mesh): built in %.1f s, peak RSS %.0f MB (%.0f MB before), %u levels, "
                "%zu clusters at level 0, %zu in all, %zu groups (%zu kept), %zu roots\n",
                tile.triangleCount(), double(tile.memoryBytes()) / 1e6, rep.seconds, double(peak) / 1024.0,
                double(before) / 1024.0, h.levels, rep.clustersPerLevel.front(), h.clusters.size(), rep.groups,
                rep.groupsKept, rep.roots);
    std::printf("%-16s %12s %10s %10s %12s %14s\n", "flight point", "triangles", "share", "clusters", "cut ms",
                "LOD chain tris");
    for (int k = 0; k < 6; ++k) {
      const float x = 100.0f + 160.0f * float(k), y = 150.0f + 140.0f * float(k);
      const glm::vec3 eye(x, y, groundNear(tile, x, y) + 40.0f);
      const double t0 = bench::nowSeconds();
      const std::vector<uint32_t> cut = mesh::selectClusterCut(h, eye, focal, 1.0f);
      const double ms = (bench::nowSeconds() - t0) * 1e3;
      const size_t tris = mesh::summariseCut(h, cut).triangles;
      char name[32];
      std::snprintf(name, sizeof name, "(%.0f, %.0f)", double(x), double(y));
      std::printf("%-16s %12zu %9.1f%% %10zu %12.2f %14zu\n", name, tris, 100.0 * double(tris) / double(tile.triangleCount()),
                  cut.size(), ms, tile.triangleCount());
      std::fflush(stdout);
    }
  }
  return 0;
}
