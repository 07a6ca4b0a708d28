// The streamed (out-of-core) cluster hierarchy build
// (meshproc/cluster_build_streamed.h) at scale, side by side with the
// in-core build (meshproc/cluster_hierarchy.h) where that fits:
//  1. per size (millions of triangles): a valley of generated scan tiles
//     (scan_valley.h) written to disk as binary PLY, read back one tile at
//     a time by the project's PLY reader; the build's time (read,
//     partition, cells), peak RSS, scratch and page bytes, cells, levels;
//     the in-core build of the same tiles (merged in memory as a
//     multi-tile import does) for sizes up to --in-core-up-to;
//  2. along a low flight over the valley (40 m above the ground, 1920x1080
//     at 50 degrees, 1 px): the cut's triangles and clusters, its time on
//     the CPU, and the bytes of the pages it needs, against the whole scan
//     (today's per-instance LOD chain draws level 0 everywhere from
//     inside the scan).
// Peak RSS is reset between sizes (/proc/self/clear_refs), so each row's
// peak is its own.
// Usage: bench_clusters_streamed [--sizes 5,20] [--in-core-up-to 5]
//        [--tile-millions 1] [--work-dir DIR] [--estimate]
//   --estimate: groups' errors from the decimator's quadric estimate, not
//   the certified bound (7x faster build; bench_clusters compares them).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/mesh_export.h"
#include "mesh/mesh_import.h"
#include "mesh/tile_merge.h"
#include "meshproc/cluster_build_streamed.h"
#include "meshproc/cluster_cut.h"
#include "meshproc/cluster_hierarchy.h"
#include "scan_valley.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

// Tiles read back from disk one at a time, as the import does.
class PlyTiles : public mesh::ScanTileSource {
 public:
  explicit PlyTiles(std::vector<std::string> paths) : paths_(std::move(paths)) {}
  size_t tileCount() const override { return paths_.size(); }
  bool readTile(size_t i, mesh::MeshData& out, std::string& error) override {
    mesh::ImportOptions o;
    o.up = mesh::UpAxis::Z;
    mesh::ImportResult r = mesh::importMesh(paths_[i], o);
    if (!r.mesh) {
      error = r.error;
      return false;
    }
    out = std::move(*r.mesh);
    return true;
  }

 private:
  std::vector<std::string> paths_;
};

void resetPeak() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

double mb(double bytes) { return bytes / 1e6; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes = {5.0, 20.0};
  double inCoreUpTo = 5.0, tileMillions = 1.0;
  std::string work = (fs::temp_directory_path() / "hs-bench-streamed").string();
  bool estimate = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sizes" && i + 1 < argc) sizes = bench::numberList(argv[++i]);
    else if (a == "--in-core-up-to" && i + 1 < argc) inCoreUpTo = std::atof(argv[++i]);
    else if (a == "--tile-millions" && i + 1 < argc) tileMillions = std::atof(argv[++i]);
    else if (a == "--work-dir" && i + 1 < argc) work = argv[++i];
    else if (a == "--estimate") estimate = true;
    else {
      std::fprintf(stderr, "usage: %s [--sizes 5,20] [--in-core-up-to 5] [--tile-millions 1] [--work-dir DIR] [--estimate]\n",
                   argv[0]);
      return 2;
    }
  }
  std::printf("bench_clusters_streamed: %s, %s, group errors: %s\n", bench::threadsText().c_str(),
              bench::loadAverageLine().c_str(), estimate ? "quadric estimate" : "certified bound");
  const float focal = 540.0f / std::tan(glm::radians(25.0f));  // 1920x1080, 50 degrees vertical
  mesh::ClusterOptions clusterOptions;
  clusterOptions.certifyErrors = !estimate;

  std::printf("\n| build | triangles | tiles | write s | read s | partition s | cells s | total s | peak RSS MB | "
              "scratch MB | pages MB | index MB | cells | levels | clusters |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> flights;
  for (double millions : sizes) {
    const bench::ValleyLayout layout = bench::valleyLayout(millions, tileMillions);
    const fs::path dir = fs::path(work) / (std::to_string(int(millions)) + "M");
    fs::create_directories(dir);
    // The tiles on disk (kept between runs: written once per size).
    double writeSeconds = 0.0;
    std::vector<std::string> paths;
    for (int tj = 0; tj < layout.tilesY; ++tj)
      for (int ti = 0; ti < layout.tilesX; ++ti) {
        const std::string path = (dir / ("tile_" + std::to_string(ti) + "_" + std::to_string(tj) + ".ply")).string();
        paths.push_back(path);
        if (fs::exists(path)) continue;
        const double t0 = bench::nowSeconds();
        const mesh::MeshData tile = bench::valleyTile(layout, ti, tj);
        mesh::ExportOptions eo;
        eo.format = mesh::ExportFormat::Ply;
        eo.zUp = true;
        eo.world = true;
        const mesh::ExportResult r = mesh::exportMesh(tile, path, eo);
        if (!r.ok()) {
          std::fprintf(stderr, "%s\n", r.error.c_str());
          return 1;
        }
        writeSeconds += bench::nowSeconds() - t0;
      }

    // The streamed build: pages to a file, counted.
    resetPeak();
    const size_t before = bench::statusKiB("VmHWM:");
    PlyTiles source(paths);
    mesh::StreamedClusterOptions so;
    so.clusters = clusterOptions;
    so.scratchDir = dir.string();
    uint64_t pageBytes = 0;
    std::vector<uint32_t> pageSizes;
    std::ofstream pagesOut(dir / "pages.bin", std::ios::binary);
    mesh::StreamedClusterReport rep;
    std::string error;
    const std::optional<mesh::ClusterIndex> index = mesh::buildClusterPagesStreamed(
        source, so,
        [&](std::vector<uint8_t>&& page, std::string& e) {
          pagesOut.write(reinterpret_cast<const char*>(page.data()), std::streamsize(page.size()));
          pageBytes += page.size();
          pageSizes.push_back(uint32_t(page.size()));
          if (!pagesOut) e = "pages.bin: cannot write";
          return bool(pagesOut);
        },
        &rep, nullptr, error);
    pagesOut.close();
    fs::remove(dir / "pages.bin");
    if (!index) {
      std::fprintf(stderr, "streamed build: %s\n", error.c_str());
      return 1;
    }
    const size_t peak = bench::statusKiB("VmHWM:");
    (void)before;
    const double indexBytes = double(index->clusters.size() * sizeof(mesh::ClusterIndexEntry));
    std::printf("| streamed | %zu | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %.0f | %.0f | %.1f | %zu | %zu | %zu |\n",
                rep.triangles, rep.tiles, writeSeconds, rep.readSeconds, rep.partitionSeconds, rep.buildSeconds,
                rep.build.seconds, double(peak) / 1024.0, mb(double(rep.scratchBytes)), mb(double(pageBytes)),
                mb(indexBytes), rep.cells, rep.build.clustersPerLevel.size(), index->clusters.size());
    std::fflush(stdout);

    // The same tiles in core, merged as a multi-tile import merges them.
    if (millions <= inCoreUpTo) {
      resetPeak();
      const double t0 = bench::nowSeconds();
      std::vector<mesh::MeshData> tiles;
      for (size_t t = 0; t < paths.size(); ++t) {
        mesh::MeshData m;
        std::string e;
        source.readTile(t, m, e);
        tiles.push_back(std::move(m));
      }
      const mesh::MeshData merged = mesh::mergeTiles(std::move(tiles), 1e-3);
      const double read = bench::nowSeconds() - t0;
      mesh::ClusterBuildReport r;
      const mesh::ClusterHierarchy h = mesh::buildClusterHierarchy(merged, clusterOptions, &r);
      const mesh::ClusterPages pages = mesh::paginate(h);
      uint64_t bytes = 0;
      for (const auto& p : pages.pages) bytes += p.size();
      const size_t inPeak = bench::statusKiB("VmHWM:");
      std::printf("| in core | %zu | %zu | | %.1f | | %.1f | %.1f | %.0f | | %.0f | %.1f | | %u | %zu |\n",
                  merged.triangleCount(), paths.size(), read, r.seconds, read + r.seconds, double(inPeak) / 1024.0,
                  mb(double(bytes)), mb(double(h.clusters.size() * sizeof(mesh::ClusterIndexEntry))), h.levels,
                  h.clusters.size());
      std::fflush(stdout);
    }

    // The flight over the streamed index.
    const mesh::ClusterGroups groups = mesh::clusterGroupsOf(*index);
    char head[160];
    std::snprintf(head, sizeof head, "\n%gM triangles (%zu): a low flight, 1 px\n", millions, rep.triangles);
    std::string table = head;
    // "every cluster": the same cut from each cluster's own test over the
    // whole index (as selectClusterCut, and a compute pass, would take it):
    // the walk's reference in time and in what it picks.
    table += "| flight point | triangles | share | clusters | groups tested | of all | cut ms | every cluster ms | "
             "same cut | pages MB needed | of all pages | LOD chain tris |\n";
    table += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (int k = 0; k < 6; ++k) {
      const double fx = 0.1 + 0.16 * k, fy = 0.15 + 0.14 * k;
      const glm::dvec3 world = layout.pointAt(fx, fy, 40.0);
      mesh::CutViewer v;
      v.eye = glm::vec3(world - index->origin);
      v.focalPx = focal;
      v.pixelBound = 1.0f;
      const double t0 = bench::nowSeconds();
      const mesh::ResidentCut cut = mesh::selectResidentCut(*index, groups, v, [](uint32_t) { return true; });
      const double ms = (bench::nowSeconds() - t0) * 1e3;
      const double t1 = bench::nowSeconds();
      std::vector<uint32_t> scanned;
      for (uint32_t id = 0; id < index->clusters.size(); ++id) {
        const mesh::ClusterIndexEntry& e = index->clusters[id];
        if (mesh::lodFineEnough(e.lodBounds, e.error, v.eye, v.focalPx, v.pixelBound) &&
            !mesh::lodFineEnough(e.parentBounds, e.parentError, v.eye, v.focalPx, v.pixelBound))
          scanned.push_back(id);
      }
      const double scanMs = (bench::nowSeconds() - t1) * 1e3;
      std::vector<uint32_t> onlyOne;
      std::set_symmetric_difference(cut.clusters.begin(), cut.clusters.end(), scanned.begin(), scanned.end(),
                                    std::back_inserter(onlyOne));
      const std::string same = onlyOne.empty() ? "yes" : std::to_string(onlyOne.size()) + " differ";
      size_t tris = 0;
      std::vector<uint32_t> pages;
      for (uint32_t id : cut.clusters) {
        tris += index->clusters[id].triangleCount;
        pages.push_back(index->clusters[id].page);
      }
      std::sort(pages.begin(), pages.end());
      pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
      uint64_t needed = 0;
      for (uint32_t p : pages) needed += pageSizes[p];
      char row[320];
      std::snprintf(row, sizeof row,
                    "| (%.2f, %.2f) | %zu | %.2f%% | %zu | %zu | %.2f%% | %.2f | %.2f | %s | %.1f | %.2f%% | %zu |\n", fx,
                    fy, tris, 100.0 * double(tris) / double(rep.triangles), cut.clusters.size(), cut.groupsTested,
                    100.0 * double(cut.groupsTested) / double(std::max<uint32_t>(index->groupCount, 1)), ms, scanMs,
                    same.c_str(), mb(double(needed)), 100.0 * double(needed) / double(pageBytes), rep.triangles);
      table += row;
    }
    flights.push_back(table);
  }
  for (const std::string& t : flights) std::printf("%s", t.c_str());
  return 0;
}
