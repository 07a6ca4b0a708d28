// bench_tile_workers: what reading the tiles of one scan through the import
// worker costs per tile, before and after keeping one worker for all tiles
// (issue 11 item 6; scene/import_isolation.h, ImportWorkerPool).
//
//   bench_tile_workers [--tiles T] [--grid N] [--runs R] [--dir FOLDER]
//
// Writes T binary PLY tiles of N x N quads (2 N^2 triangles each; defaults
// 16 and 60) and reads every tile with Assimp's PLY reader (reader=assimp,
// so each goes through the worker) three ways, one tile at a time so that
// only the worker's start differs:
//   in process   mesh::importMesh here, no worker (the floor)
//   new worker   one worker started per tile (scene::importMeshIsolated,
//                what multi-tile imports did before)
//   kept worker  one ImportWorkerPool for all tiles (what they do now)
// Median over R runs of the whole set; per-tile columns are that / T.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/mesh_import.h"
#include "scene/import_isolation.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

// A grid tile of n x n quads at column `tile`, float x y z, binary LE.
void writeTile(const std::string& path, int tile, int n) {
  std::ofstream f(path, std::ios::binary);
  const int v = (n + 1) * (n + 1);
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << v
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2 * n * n
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float p[3] = {float(tile * n + i), float(j), float((i * 7 + j * 13) % 5) * 0.1f};
      f.write(reinterpret_cast<const char*>(p), sizeof p);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      const unsigned char three = 3;
      const int t0[3] = {a, b, c}, t1[3] = {a, c, d};
      f.write(reinterpret_cast<const char*>(&three), 1);
      f.write(reinterpret_cast<const char*>(t0), sizeof t0);
      f.write(reinterpret_cast<const char*>(&three), 1);
      f.write(reinterpret_cast<const char*>(t1), sizeof t1);
    }
}

}  // namespace

int main(int argc, char** argv) {
  int tiles = 16, grid = 60, runs = 5;
  std::string dir = fs::temp_directory_path().string();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--tiles" && i + 1 < argc) tiles = std::atoi(argv[++i]);
    else if (a == "--grid" && i + 1 < argc) grid = std::atoi(argv[++i]);
    else if (a == "--runs" && i + 1 < argc) runs = std::atoi(argv[++i]);
    else if (a == "--dir" && i + 1 < argc) dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_tile_workers [--tiles T] [--grid N] [--runs R] [--dir FOLDER]\n");
      return 2;
    }
  }
  if (tiles < 1 || grid < 1 || runs < 1) {
    std::fprintf(stderr, "bench_tile_workers: --tiles, --grid and --runs need positive numbers\n");
    return 2;
  }
  std::vector<std::string> paths;
  for (int t = 0; t < tiles; ++t) {
    paths.push_back(dir + "/bench_tile_" + std::to_string(t) + ".ply");
    writeTile(paths.back(), t, grid);
  }
  mesh::ImportOptions options;
  options.reader = mesh::Reader::Assimp;
  options.up = mesh::UpAxis::Z;

  struct Way {
    const char* name;
    std::vector<double> seconds;
    unsigned workers = 0;
  };
  Way ways[3] = {{"in process (no worker)", {}, 0}, {"new worker per tile (before)", {}, 0},
                 {"kept worker, one pool (now)", {}, 0}};
  bool ok = true;
  // Interleaved: each run does all three ways, so load changes hit all alike.
  for (int r = 0; r < runs; ++r)
    for (int w = 0; w < 3; ++w) {
      const double t0 = bench::nowSeconds();
      scene::ImportWorkerPool pool;
      for (const std::string& p : paths) {
        const mesh::ImportResult res = w == 0   ? mesh::importMesh(p, options)
                                       : w == 1 ? scene::importMeshIsolated(p, options)
                                                : pool.read(p, options);
        if (!res.ok()) {
          std::fprintf(stderr, "bench_tile_workers: %s\n", res.error.c_str());
          ok = false;
        }
      }
      ways[w].seconds.push_back(bench::nowSeconds() - t0);
      ways[w].workers = w == 2 ? pool.workersStarted() : w == 1 ? unsigned(tiles) : 0;
    }
  for (const std::string& p : paths) fs::remove(p);
  if (!ok) return 1;

  std::printf("%d tiles of %d triangles (binary PLY, Assimp's reader), %d runs, median; load: %s\n\n", tiles,
              2 * grid * grid, runs, bench::loadAverageLine().c_str());
  std::printf("| reading | workers started | all tiles s | per tile ms | over in-process, per tile ms |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: |\n");
  const double floor = bench::median(ways[0].seconds);
  for (const Way& w : ways) {
    const double all = bench::median(w.seconds);
    std::printf("| %s | %u | %.3f | %.1f | %.1f |\n", w.name, w.workers, all, 1000.0 * all / tiles,
                1000.0 * (all - floor) / tiles);
  }
  return 0;
}
