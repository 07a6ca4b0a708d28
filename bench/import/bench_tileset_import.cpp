// A 3D Tiles tileset imported two ways (scene/tileset_import.h): in core
// (every tile decoded, its tree kept as the hierarchy) and streamed
// (scene/tileset_import_streamed.h: the tree read without decoding, the
// finest tiles decoded one at a time into a hierarchy built out of core).
// The tileset is generated: a quadtree of `--depth` levels over a bumpy
// valley at Meteora (an east-north-up transform, so the import converts
// ECEF to UTM through PROJ as it does for a real one), each tile a grid of
// 180 x 180 quads (64,800 triangles) as a glb; depth 3 gives 64 leaves
// (4.1M triangles, 5.5M over all levels), depth 4 256 (16.6M, 22.1M).
// Each import runs in a process of its own (fork), so its peak resident
// set is its own. Columns: time, peak RSS, level-0 triangles, levels.
// Usage: bench_tileset_import [--depths 3,4] [--work-dir DIR] [--estimate]
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"
#include "tests/common/tileset_files.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

constexpr double kSide = 4000.0;  // metres: the valley's square
constexpr int kCells = 180;

double valley(double e, double n) {
  return 60.0 * std::sin(e / 310.0) * std::cos(n / 270.0) + 12.0 * std::sin(e / 37.0 + n / 53.0) + 0.002 * e;
}

// Tile (level, x, y) and its children down to `depth`; returns its JSON.
Json writeTile(const std::string& dir, int level, int x, int y, int depth, size_t& triangles) {
  const double size = kSide / double(1 << level);
  const double e0 = -kSide / 2 + size * x, n0 = -kSide / 2 + size * y;
  const test::TestGrid g = test::testGrid(e0, e0 + size, n0, n0 + size, kCells, valley);
  const std::string name = std::to_string(level) + "_" + std::to_string(x) + "_" + std::to_string(y) + ".glb";
  const glm::dvec3 centre(e0 + size / 2, n0 + size / 2, 0.0);
  // Positions in the tileset's east-north-up frame (floats: 0.2 mm steps at 2 km).
  test::writeBytes(dir + "/" + name, test::glbOf(g));
  triangles += g.triangles.size() / 3;
  Json t = {{"boundingVolume", {{"sphere", {centre.x, centre.y, 0.0, size}}}},
            {"geometricError", level == depth ? 0.0 : size / kCells},
            {"content", {{"uri", name}}}};
  if (level < depth) {
    t["children"] = Json::array();
    for (int c = 0; c < 4; ++c) t["children"].push_back(writeTile(dir, level + 1, 2 * x + (c & 1), 2 * y + (c >> 1), depth, triangles));
  }
  return t;
}

struct Result {
  double seconds = 0, peakMb = 0;
  size_t level0 = 0, levels = 0;
  bool ok = false;
  char error[512] = {};
};

Result importOnce(const std::string& tileset, scene::MeshImportRequest::Clusters mode, bool estimate,
                  const std::string& scratch) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    Result r;
    scene::MeshImportRequest q;
    q.files = {tileset};
    q.clusters = mode;
    q.scratchDir = scratch;
    if (estimate) q.clusterOptions.certifyErrors = false;
    const double t0 = bench::nowSeconds();
    const scene::ImportedMesh m = scene::importMeshFiles(q);
    r.seconds = bench::nowSeconds() - t0;
    r.peakMb = double(bench::statusKiB("VmHWM:")) / 1024.0;
    r.ok = m.ok();
    if (r.ok) {
      r.level0 = m.clusters->triangles(0);
      r.levels = m.clusters->levels();
    } else {
      std::snprintf(r.error, sizeof r.error, "%s", m.error.c_str());
    }
    if (write(fds[1], &r, sizeof r) != ssize_t(sizeof r)) _exit(1);
    _exit(0);
  }
  close(fds[1]);
  Result r;
  if (read(fds[0], &r, sizeof r) != ssize_t(sizeof r)) std::snprintf(r.error, sizeof r.error, "the child died");
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> depths = {3, 4};
  std::string work = (fs::temp_directory_path() / "hs-bench-tileset").string();
  bool estimate = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--depths" && i + 1 < argc) depths = bench::numberList(argv[++i]);
    else if (a == "--work-dir" && i + 1 < argc) work = argv[++i];
    else if (a == "--estimate") estimate = true;
    else {
      std::fprintf(stderr, "usage: bench_tileset_import [--depths 3,4] [--work-dir DIR] [--estimate]\n");
      return 2;
    }
  }
  std::printf("# bench_tileset_import: a generated tileset in core and streamed (%s errors)\n",
              estimate ? "estimated" : "certified");
  std::printf("# %s, threads: %s\n", bench::loadAverageLine().c_str(), bench::threadsText().c_str());
  std::printf("%-6s %-10s %-10s %-9s %10s %10s %12s %7s\n", "depth", "tiles", "triangles", "mode", "seconds",
              "peak MB", "level-0 tris", "levels");
  for (double d : depths) {
    const int depth = int(d);
    const std::string dir = work + "/depth" + std::to_string(depth);
    fs::remove_all(dir);
    fs::create_directories(dir);
    size_t triangles = 0;
    Json root = writeTile(dir, 0, 0, 0, depth, triangles);
    root["transform"] = test::matrixJson(test::enuToEcef(21.63, 39.72, 300.0));
    root["refine"] = "REPLACE";
    test::writeText(dir + "/tileset.json",
                    Json{{"asset", {{"version", "1.1"}}}, {"geometricError", kSide / kCells * 2}, {"root", root}}.dump());
    size_t tiles = 0;
    for (int l = 0; l <= depth; ++l) tiles += size_t(1) << (2 * l);
    for (auto mode : {scene::MeshImportRequest::Clusters::On, scene::MeshImportRequest::Clusters::Streamed}) {
      const Result r = importOnce(dir + "/tileset.json", mode, estimate, work);
      const char* name = mode == scene::MeshImportRequest::Clusters::On ? "in core" : "streamed";
      if (!r.ok) {
        std::printf("%-6d %-10zu %-10zu %-9s failed: %s\n", depth, tiles, triangles, name, r.error);
        continue;
      }
      std::printf("%-6d %-10zu %-10zu %-9s %10.1f %10.0f %12zu %7zu\n", depth, tiles, triangles, name, r.seconds,
                  r.peakMb, r.level0, r.levels);
      std::fflush(stdout);
    }
    fs::remove_all(dir);
  }
  return 0;
}
