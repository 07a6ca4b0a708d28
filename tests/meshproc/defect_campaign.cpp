// A seeded campaign of defective surfaces through the whole processing
// (docs/reliability.md, "Defective surfaces through the decimator"): grids
// of 10-50 cells, flat or curved, with or without a UV seam, a third with
// two materials, some at UTM coordinates, each with up to 14 scan defects of the kinds
// hs::test::addDefect makes, scaled to 1 cm, 10 m or 10 km across,
// cleaned, decimated to 2%, 10%, 50% or a maximum error of 0.5% of the
// grid's size, with 0-2 LOD levels and the error report, on one thread
// and on two (the cases and the checks: defect_cases.h).
//
//   meshproc_defect_campaign [--trials N] [--seed S] [--only T [--without D]] [--retries R] [--export DIR]
//
// --retries R sets ProcessOptions::maxErrorRetries (default: its default);
// the summary gives the runs and the triangles kept over the maximum-error
// cases, to compare policies on the same meshes.
// --export DIR also writes each result as OBJ, PLY and GLB into DIR and
// reads it back (checkExportRoundTrip in defect_cases.h).
// --only T runs trial T alone (the same mesh as in the whole run);
// --without D leaves its D-th defect (from 0) out, to find which one a
// failure needs.
// Prints each failing case (seed and trial reproduce it) and a count; exits
// 1 when any failed. Not a test: the tests hold the cases it found
// (test_meshproc_clean, test_meshproc_decimate, test_meshproc_error, which
// replays the campaign's cases by seed and trial).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "defect_cases.h"

int main(int argc, char** argv) {
  int trials = 300, only = -1, without = -1, retries = -1;
  std::string exportDir;
  unsigned seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--trials")) trials = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seed")) seed = unsigned(std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--only")) only = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--without")) without = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--retries")) retries = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--export")) exportDir = argv[i + 1];
    else {
      std::fprintf(stderr, "usage: %s [--trials N] [--seed S] [--only T [--without D]] [--retries R] [--export DIR]\n", argv[0]);
      return 2;
    }
  }
  // A folder that is not there is made (every case's export would fail
  // on it, 2,000 failures saying the same thing).
  if (std::error_code ec; !exportDir.empty() && !std::filesystem::is_directory(exportDir) &&
                          !std::filesystem::create_directories(exportDir, ec)) {
    std::fprintf(stderr, "--export %s: cannot create it: %s\n", exportDir.c_str(), ec.message().c_str());
    return 2;
  }
  hs::test::DefectCases cases(seed);
  int failed = 0, maxErrorRuns = 0, runsMost = 0;
  double runsSum = 0, keptSum = 0;  // over the maximum-error cases, one thread
  for (int trial = 0; trial < trials; ++trial) {
    hs::test::DefectCase c = cases.next(trial == only ? without : -1);
    if (only >= 0 && trial != only) continue;
    if (retries >= 0) c.options.maxErrorRetries = retries;
    const hs::test::DefectOutcome r =
        hs::test::checkDefectCase(c, exportDir.empty() ? std::string() : exportDir + "/case");
    for (const std::string& f : r.failures) std::printf("%s: %s\n", c.where.c_str(), f.c_str());
    failed += !r.failures.empty();
    if (c.target == 3) {
      ++maxErrorRuns;
      runsSum += r.runs;
      runsMost = std::max(runsMost, r.runs);
      keptSum += r.kept;
    }
  }
  std::printf("%d of %d cases failed (%d with a maximum error)\n", failed, only >= 0 ? 1 : trials, maxErrorRuns);
  if (maxErrorRuns > 0)
    std::printf("maximum-error cases: %.3f runs on average, at most %d; "
                "%.2f%% of the input's triangles kept on average\n",
                runsSum / maxErrorRuns, runsMost, 100.0 * keptSum / maxErrorRuns);
  return failed ? 1 : 0;
}
