// A seeded campaign of defective surfaces through the whole processing
// (docs/reliability.md, "Defective surfaces through the decimator"): grids
// of 10-50 cells, flat or curved, with or without a UV seam, a third with
// two materials, some at UTM coordinates, each with up to 14 scan defects of the kinds
// hs::test::addDefect makes, scaled to 1 cm, 10 m or 10 km across,
// cleaned, decimated to 2%, 10%, 50% or a maximum error of 0.5% of the
// grid's size, with 0-2 LOD levels and the error report, on one thread
// and on two. Every result must be valid (indices in range, no face
// repeating a vertex, finite positions), the same on both thread counts,
// with no boundary or seam vertex off the input's polylines, a Hausdorff
// below 5% of the diagonal (2% targets aside: a handful of triangles
// cannot follow a small grid), and a maximum error met as measured.
//
//   meshproc_defect_campaign [--trials N] [--seed S] [--only T [--without D]] [--retries R]
//
// --retries R sets ProcessOptions::maxErrorRetries (default: its default);
// the summary gives the runs and the triangles kept over the maximum-error
// cases, to compare policies on the same meshes.
// --only T runs trial T alone (the same mesh as in the whole run);
// --without D leaves its D-th defect (from 0) out, to find which one a
// failure needs.
// Prints each failing case (seed and trial reproduce it) and a count; exits
// 1 when any failed. Not a test: the tests hold the cases it found
// (test_meshproc_clean, test_meshproc_decimate, test_meshproc_error).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "meshproc/error_metrics.h"
#include "meshproc/mesh_process.h"
#include "mesh_builders.h"

using namespace hs::mesh;

int main(int argc, char** argv) {
  int trials = 300, only = -1, without = -1, retries = -1;
  unsigned seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--trials")) trials = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seed")) seed = unsigned(std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--only")) only = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--without")) without = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--retries")) retries = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: %s [--trials N] [--seed S] [--only T [--without D]] [--retries R]\n", argv[0]);
      return 2;
    }
  }
  std::mt19937 rng(seed);
  int failed = 0, maxErrorRuns = 0;
  double runsSum = 0, keptSum = 0;  // over the maximum-error cases, one thread
  int runsMost = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const int n = 10 + int(rng() % 41);
    const bool seam = rng() % 2 == 0;
    MeshData grid = hs::test::curvedGrid(n, 10.0, 0.3 * double(rng() % 3), seam);
    const bool utm = rng() % 4 == 0;
    if (utm) grid.origin = glm::dvec3(656059.0, 5514553.0, 1713.0);
    if (rng() % 3 == 0) {
      // Two materials, split down the middle (a material border is a seam).
      std::vector<uint32_t> left, right;
      for (size_t f = 0; f < grid.triangleCount(); ++f) {
        const float cx = (grid.positions[grid.indices[f * 3]].x + grid.positions[grid.indices[f * 3 + 1]].x +
                          grid.positions[grid.indices[f * 3 + 2]].x) / 3.0f;
        auto& side = cx < 5.0f ? left : right;
        side.insert(side.end(), grid.indices.begin() + f * 3, grid.indices.begin() + f * 3 + 3);
      }
      grid.indices = left;
      grid.indices.insert(grid.indices.end(), right.begin(), right.end());
      grid.materials.resize(2);
      grid.submeshes = {{0, uint32_t(left.size()), 0}, {uint32_t(left.size()), uint32_t(right.size()), 1}};
    }
    MeshData in = grid;
    const int defects = int(rng() % 15);
    std::string kinds;
    for (int d = 0; d < defects; ++d) {
      const int kind = int(rng() % 11);
      kinds += (kinds.empty() ? "" : ",") + std::to_string(kind);
      if (d == without && trial == only) {
        MeshData scratch = grid;  // left out, with the same draws: later defects stay where they were
        hs::test::addDefect(scratch, grid, kind, rng);
      } else {
        hs::test::addDefect(in, grid, kind, rng);
      }
    }
    // A 1 cm object, the 10 m patch, or 10 km of terrain: the same shape.
    const double scales[] = {1e-3, 1.0, 1e3};
    const double scale = scales[rng() % 3];
    for (auto& p : in.positions) p *= float(scale);
    ProcessOptions o;
    o.decimate = true;
    if (retries >= 0) o.maxErrorRetries = retries;
    const int target = int(rng() % 4);
    const double ratios[] = {0.02, 0.1, 0.5};
    if (target < 3) {
      o.decimation.targetRatio = ratios[target];
    } else {
      o.decimation.targetRatio = 0;
      o.decimation.maxError = 0.05 * scale;
      ++maxErrorRuns;
    }
    o.decimation.lockBoundaries = rng() % 5 == 0;
    o.decimation.facesPerRegion = 1000;
    o.lodLevels = int(rng() % 3);
    o.error.samplesPerFace = 2;
    if (only >= 0 && trial != only) continue;
    char where[256];
    std::snprintf(where, sizeof where, "seed %u trial %d: %dx%d grid x %g%s%s%s, defects [%s], %s%s", seed, trial, n, n, scale,
                  seam ? ", seam" : "", grid.submeshes.size() > 1 ? ", 2 materials" : "", utm ? ", UTM" : "", kinds.c_str(),
                  target < 3 ? (std::to_string(int(ratios[target] * 100)) + "%").c_str() : "max error 0.05 m x scale",
                  o.decimation.lockBoundaries ? ", borders locked" : "");
    uint64_t hashes[2] = {0, 0};
    bool bad = false;
    auto fail = [&](const std::string& what) {
      std::printf("%s: %s\n", where, what.c_str());
      bad = true;
    };
    for (unsigned threads : {1u, 2u}) {
      o.decimation.threads = o.error.threads = o.cleaning.threads = threads;
      const ProcessResult r = processMesh(in, o);
      if (!r.ok()) {
        fail("refused: " + r.error);
        break;
      }
      const MeshData& out = r.mesh;
      for (size_t t = 0; t < out.triangleCount(); ++t) {
        const uint32_t i = out.indices[t * 3], j = out.indices[t * 3 + 1], l = out.indices[t * 3 + 2];
        if (i >= out.vertexCount() || j >= out.vertexCount() || l >= out.vertexCount() || i == j || j == l || i == l) {
          fail("face " + std::to_string(t) + " is invalid");
          break;
        }
      }
      for (const auto& p : out.positions)
        if (!std::isfinite(p.x + p.y + p.z)) {
          fail("a position is not finite");
          break;
        }
      for (const MeshData& level : r.lods)
        for (uint32_t i : level.indices)
          if (i >= level.vertexCount()) {
            fail("a LOD level's index is out of range");
            break;
          }
      const ErrorReport& e = r.report.error;
      if (threads == 1 && target == 3) {
        runsSum += r.report.maxErrorPasses;
        runsMost = std::max(runsMost, r.report.maxErrorPasses);
        keptSum += double(out.triangleCount()) / double(in.triangleCount());
      }
      if (threads == 1) {
        if (e.constrainedVerticesMoved)
          fail(std::to_string(e.constrainedVerticesMoved) + " boundary/seam vertices off the input's, by up to " +
               std::to_string(e.constrainedMaxDeviation) + " m");
        if (target != 0 && !(e.rel(e.hausdorff) < 0.05)) fail("Hausdorff " + std::to_string(e.rel(e.hausdorff)) + " of the diagonal");
        if (target == 3 && !(e.hausdorff <= o.decimation.maxError))
          fail("maximum error not met: " + std::to_string(int(std::round(100.0 * (e.hausdorff / o.decimation.maxError - 1.0)))) +
               "% over after " + std::to_string(r.report.maxErrorPasses) + " runs");
      }
      hashes[threads - 1] = contentHash(out);
    }
    if (!bad && hashes[0] != hashes[1]) fail("differs between 1 and 2 threads");
    failed += bad;
  }
  std::printf("%d of %d cases failed (%d with a maximum error)\n", failed, trials, maxErrorRuns);
  if (maxErrorRuns > 0 && only < 0)
    std::printf("maximum-error cases: %.3f runs on average, at most %d; %.2f%% of the input's triangles kept on average\n",
                runsSum / maxErrorRuns, runsMost, 100.0 * keptSum / maxErrorRuns);
  return failed ? 1 : 0;
}
